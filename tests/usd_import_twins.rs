//! USD layers the USD library wrote in both forms (`scripts/usd/author_twins.py`, in
//! `tests/data/usd/`): every text layer reads as its ops, knots and trims say, checked here
//! against transforms and points worked out from the file's text; every binary layer (with the
//! `usd-binary` feature) reads to the same patches, parts and motion as its text twin; and the
//! compositions glint refuses are refused in both forms with one line and exit 2.

use glam::{DMat3, DMat4, DQuat, DVec3};
use glint::formats::{load_model, load_patches};

use crate::common::{glint_with as glint, repo_file, stderr};
use crate::usd_motion::{in_net_order, tuples};

/// The twins that read: every supported xformOp nested, ops in half precision, both knot
/// conventions, trim ranges narrower than their knots, and time samples.
const READ: [&str; 5] = ["xform_ops", "half_ops", "knots", "trim_ranges", "animated"];

fn fixture(name: &str) -> std::path::PathBuf {
    repo_file(&format!("tests/data/usd/{name}"))
}

fn text(name: &str) -> String {
    std::fs::read_to_string(fixture(&format!("{name}.usda"))).unwrap()
}

/// The control points of prim `prim` (the first `points = [...]` after `def NurbsPatch
/// "PRIM"`) in `text`, in glint's net order.
fn points_of(text: &str, prim: &str, nu: usize, nv: usize) -> Vec<DVec3> {
    let start = text
        .find(&format!("def NurbsPatch \"{prim}\""))
        .unwrap_or_else(|| panic!("no prim {prim}"));
    let after = &text[start..];
    let from = after.find("point3f[] points = [").unwrap() + "point3f[] points = ".len();
    let to = from + after[from..].find(']').unwrap() + 1;
    in_net_order(&tuples(&after[from..to]), nu, nv)
}

fn degrees(x: f64) -> f64 {
    x.to_radians()
}

/// `rotateABC = (x, y, z)` as USD defines it: about A first, then B, then C, each by its own
/// component: `R = R_C · R_B · R_A` for column vectors.
fn euler(order: &str, (x, y, z): (f64, f64, f64)) -> DMat4 {
    let about = |axis: char| match axis {
        'X' => DMat4::from_rotation_x(degrees(x)),
        'Y' => DMat4::from_rotation_y(degrees(y)),
        _ => DMat4::from_rotation_z(degrees(z)),
    };
    let c: Vec<char> = order.chars().collect();
    about(c[2]) * about(c[1]) * about(c[0])
}

fn assert_close(got: &[DVec3], expected: &[DVec3], what: &str) {
    assert_eq!(got.len(), expected.len(), "{what}");
    for (k, (g, e)) in got.iter().zip(expected).enumerate() {
        assert!(
            (*g - *e).length() < 1e-6,
            "{what}, point {k}: {g} where the ops give {e}"
        );
    }
}

#[test]
fn nested_transforms_of_every_op_place_the_patches_as_the_ops_say() {
    let library = load_patches(&fixture("xform_ops.usda")).unwrap();
    let text = text("xform_ops");
    // The values written by the script, composed here by hand: translate · rotateXYZ · scale
    // on /rig; rotateX · rotateY · rotateZ · pivot · orient · pivot⁻¹ on /rig/arm; the five
    // other Euler orders and a matrix on /rig/arm/hand; the layer is y up, turned to z up.
    let up = DMat4::from_mat3(DMat3::from_cols(
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(0.0, -1.0, 0.0),
    ));
    let rig = DMat4::from_translation(DVec3::new(0.5, -1.25, 2.0))
        * euler("XYZ", (10.0, -25.0, 40.0))
        * DMat4::from_scale(DVec3::new(1.5, 0.8, 1.2));
    let pivot = DVec3::new(1.0, 0.5, 0.0);
    let orient = DQuat::from_xyzw(0.2, -0.4, 0.4, 0.8);
    let arm = DMat4::from_rotation_x(degrees(30.0))
        * DMat4::from_rotation_y(degrees(-15.0))
        * DMat4::from_rotation_z(degrees(75.0))
        * DMat4::from_translation(pivot)
        * DMat4::from_quat(orient)
        * DMat4::from_translation(-pivot);
    let mut hand = DMat4::IDENTITY;
    for (k, order) in ["XZY", "YXZ", "YZX", "ZXY", "ZYX"].into_iter().enumerate() {
        let k = k as f64;
        hand *= euler(order, (5.0 + 7.0 * k, -12.0 + 3.0 * k, 20.0 - 9.0 * k));
    }
    hand *= DMat4::from_rotation_translation(
        DQuat::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), degrees(33.0)),
        DVec3::new(-0.3, 0.7, 1.1),
    );
    for (name, prim, world) in [
        ("rig/base", "base", up * rig),
        ("rig/arm/upper", "upper", up * rig * arm),
        ("rig/arm/hand/palm", "palm", up * rig * arm * hand),
    ] {
        let patch = library.find(name).unwrap_or_else(|e| panic!("{e}"));
        let expected: Vec<DVec3> = points_of(&text, prim, 4, 4)
            .into_iter()
            .map(|p| world.transform_point3(p))
            .collect();
        let got: Vec<DVec3> = patch.surface.control_points().collect();
        assert_close(&got, &expected, name);
    }
}

#[test]
fn ops_written_in_half_precision_place_the_patch_as_the_ops_say() {
    let library = load_patches(&fixture("half_ops.usda")).unwrap();
    let text = text("half_ops");
    // translate · rotateXYZ · orient (120° about (1, 1, 1)) · rotateZ · scale, each value one a
    // half holds exactly.
    let rig = DMat4::from_translation(DVec3::new(0.5, -1.25, 2.0))
        * euler("XYZ", (10.0, -24.0, 40.0))
        * DMat4::from_quat(DQuat::from_xyzw(0.5, 0.5, 0.5, 0.5))
        * DMat4::from_rotation_z(degrees(30.0))
        * DMat4::from_scale(DVec3::new(1.5, 0.75, 1.25));
    let expected: Vec<DVec3> = points_of(&text, "sheet", 4, 4)
        .iter()
        .map(|&p| rig.transform_point3(p))
        .collect();
    let got: Vec<DVec3> = library.patches[0].surface.control_points().collect();
    assert_close(&got, &expected, "/rig/sheet");
}

#[test]
fn both_knot_conventions_read_to_the_same_patch() {
    // Maya's count + order − 2 knots with the end knots repeated are the whole vector: the two
    // patches differ only by the lift of their points.
    let library = load_patches(&fixture("knots.usda")).unwrap();
    let whole = &library.find("knots/whole").unwrap().surface;
    let maya = &library.find("knots/maya").unwrap().surface;
    let lift = DVec3::new(0.0, 0.0, 0.4);
    for (u, v) in [
        (0.0, 0.0),
        (0.2, 0.7),
        (0.3, 0.45),
        (0.55, 0.1),
        (0.9, 0.95),
        (1.0, 1.0),
    ] {
        let (a, b) = (whole.point(u, v), maya.point(u, v));
        assert!(
            // The lift was added to single-precision points: each rounds on its own.
            (b - a - lift).length() < 1e-6,
            "at ({u}, {v}): {a} and {b} are not the same surface lifted"
        );
    }
    // Rational and non-uniform: the surface is not its control net's bilinear blend.
    let corner = whole.control_point(0, 0).0;
    assert!((whole.point(0.0, 0.0) - corner).length() < 1e-12);
}

#[test]
fn trim_ranges_narrower_than_their_knots_close_the_loops_they_bound() {
    // The square's polyline runs on past its range, and the circle's second arc is used over
    // two thirds of its knots: read over their ranges, both loops close, and the holes are where the
    // script drew them.
    let library = load_patches(&fixture("trim_ranges.usda")).unwrap();
    let trim = library.patches[0]
        .trim
        .as_ref()
        .expect("the patch is trimmed");
    assert_eq!(trim.loops().len(), 3, "the outer loop and two holes");
    for (u, v, kept) in [
        (0.27, 0.27, false), // in the square
        (0.16, 0.39, false),
        (0.5, 0.3, true),   // between the holes
        (0.3, 0.06, true),  // where the square's curve runs on past its range
        (0.7, 0.65, false), // the circle's centre
        (0.7, 0.51, false), // just inside it, south
        (0.7, 0.49, true),  // just outside
        (0.84, 0.65, false),
        (0.86, 0.65, true),
        (0.9, 0.1, true),
    ] {
        assert_eq!(trim.contains(u, v), kept, "({u}, {v})");
    }
}

/// `glint probe` on `file`: its exit code and its standard error.
fn probe(file: &std::path::Path) -> (Option<i32>, String) {
    let out = glint(&[
        "probe",
        file.to_str().unwrap(),
        "--patch",
        "0",
        "--uv",
        "0,0",
    ]);
    (out.status.code(), stderr(&out))
}

#[test]
fn an_over_and_a_sublayer_are_refused_at_their_place() {
    for (name, needle, what) in [
        ("over", "over \"extra\"", "`over`"),
        ("sublayer", "subLayers", "`subLayers`"),
    ] {
        let file = fixture(&format!("{name}.usda"));
        let (code, err) = probe(&file);
        assert_eq!(code, Some(2), "{name}: {err}");
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        let text = text(name);
        let offset = text
            .find(needle)
            .unwrap_or_else(|| panic!("{name}: no {needle}"));
        let line = text[..offset].lines().count().max(1);
        assert!(
            err.contains(&format!("{name}.usda:{line}:")) && err.contains(what),
            "{name}: {err}"
        );
    }
}

/// Asserts that `binary` holds the patches and parts of `text`: the same names, parts and
/// domains, and the same control points and surface to within the rounding of the text's
/// single-precision numbers (`0.33333334` is the float's shortest text, not the float).
#[cfg(feature = "usd-binary")]
fn assert_same_patches(
    binary: &glint::geom::PatchLibrary,
    text: &glint::geom::PatchLibrary,
    name: &str,
) {
    assert_eq!(binary.names(), text.names(), "{name}: the patches");
    assert_eq!(binary.groups, text.groups, "{name}: the parts");
    for (b, t) in binary.patches.iter().zip(&text.patches) {
        let what = format!("{name}: {}", b.name);
        assert_eq!(b.surface.domain(), t.surface.domain(), "{what}");
        let points = |p: &glint::geom::NamedPatch| p.surface.control_points().collect::<Vec<_>>();
        assert_close(&points(b), &points(t), &what);
        let domain = b.surface.domain();
        let grid: Vec<(f64, f64)> = (0..=6)
            .flat_map(|i| (0..=6).map(move |j| domain.lerp(f64::from(i) / 6.0, f64::from(j) / 6.0)))
            .collect();
        let on = |p: &glint::geom::NamedPatch| {
            grid.iter()
                .map(|&(u, v)| p.surface.point(u, v))
                .collect::<Vec<_>>()
        };
        assert_close(&on(b), &on(t), &format!("{what}, the surface"));
        match (&b.trim, &t.trim) {
            (None, None) => {}
            (Some(bt), Some(tt)) => {
                assert_eq!(bt.loops().len(), tt.loops().len(), "{what}: trim loops");
                for (lb, lt) in bt.loops().iter().zip(tt.loops()) {
                    assert_eq!(lb.len(), lt.len(), "{what}: a loop's points");
                    for (pb, pt) in lb.iter().zip(lt) {
                        assert!((*pb - *pt).length() < 1e-9, "{what}: trim {pb} vs {pt}");
                    }
                }
            }
            _ => panic!("{what}: trimmed in one form only"),
        }
    }
}

#[cfg(feature = "usd-binary")]
#[test]
fn every_binary_twin_reads_to_its_text_twin_s_patches_and_motion() {
    for name in READ {
        let text = load_model(&fixture(&format!("{name}.usda"))).unwrap();
        let binary = load_model(&fixture(&format!("{name}.usdc"))).unwrap();
        assert_same_patches(&binary.library, &text.library, name);
        assert_eq!(binary.motion.is_some(), name == "animated", "{name}");
        if let (Some(b), Some(t)) = (&binary.motion, &text.motion) {
            assert_eq!(b.time_codes(), t.time_codes(), "{name}: the time codes");
            assert_eq!(b.moving(), t.moving(), "{name}: the patches that move");
            assert_eq!(
                b.sample_times(),
                t.sample_times(),
                "{name}: the sample times"
            );
            for &patch in b.moving() {
                for time in [-2.0, 1.0, 3.25, 10.0, 17.6, 24.0, 40.0] {
                    let what = format!("{name}: patch {patch} at time code {time}");
                    assert_close(&b.points_at(patch, time), &t.points_at(patch, time), &what);
                }
            }
        }
    }
    // The motion read: between the time codes, held at the ends.
    let binary = load_model(&fixture("animated.usdc")).unwrap();
    let motion = binary.motion.expect("the binary layer moves");
    let codes = motion.time_codes();
    assert_eq!(
        (codes.per_second, codes.frames_per_second, codes.start),
        (30.0, Some(24.0), Some(1.0))
    );
    let first = motion.points_at(0, 1.0);
    assert_ne!(motion.points_at(0, 5.5), first);
    assert_eq!(motion.points_at(0, -3.0), first);
    assert_eq!(motion.points_at(0, 24.0), motion.points_at(0, 100.0));
}

#[cfg(feature = "usd-binary")]
#[test]
fn the_binary_twins_of_refused_layers_are_refused_naming_what() {
    for (name, what) in [("over", "/sheet/extra: `over`"), ("sublayer", "sublayers")] {
        let (code, err) = probe(&fixture(&format!("{name}.usdc")));
        assert_eq!(code, Some(2), "{name}: {err}");
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(err.contains(what), "{name}: {err}");
    }
}

#[cfg(not(feature = "usd-binary"))]
#[test]
fn the_text_twins_read_where_the_binary_ones_need_the_feature() {
    for name in READ {
        load_model(&fixture(&format!("{name}.usda")))
            .unwrap_or_else(|e| panic!("{name}.usda: {e}"));
        let (code, err) = probe(&fixture(&format!("{name}.usdc")));
        assert_eq!(code, Some(2), "{name}: {err}");
        assert!(err.contains("usd-binary"), "{name}: {err}");
    }
}
