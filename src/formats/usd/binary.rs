//! A binary USD layer (`.usdc`, or a binary `.usd`) read into a [`Layer`] through the `openusd`
//! crate, as the text reader reads a text layer: its time samples and time codes, refusing
//! what the text reader refuses (composition, connected values) and splines. A binary layer has
//! no lines and columns; its errors name the prim.

use openusd::sdf::{self, AbstractData, SpecType, Specifier};

use super::layer::{Layer, LayerTimes, Prim, Property, Sample, Value, NOWHERE};

/// Prim fields that compose other layers or variants into a prim.
const COMPOSITION_FIELDS: [(&str, &str); 6] = [
    ("references", "references"),
    ("payload", "payloads"),
    ("inheritPaths", "inherits"),
    ("specializes", "specializes"),
    ("variantSetNames", "variant sets"),
    ("variantSelection", "variants"),
];

/// The most prims and child prims may nest.
const MAX_DEPTH: usize = 256;

/// The layer in the binary file at `path`, or why it cannot be read.
pub(super) fn read(path: &std::path::Path) -> Result<Layer, String> {
    let data = openusd::usdc::read_file(path)
        .map_err(|e| format!("not a readable binary USD layer: {e}"))?;
    let root = sdf::Path::from("/");
    if has(&*data, &root, "subLayers") {
        return Err("the layer has sublayers, a composition glint does not follow; flatten the stage into one layer (usdcat --flatten in.usd -o flat.usda)".to_string());
    }
    let up_axis = match field(&*data, &root, "upAxis") {
        Some(sdf::Value::Token(axis)) => Some((axis.as_ref().to_string(), NOWHERE)),
        _ => None,
    };
    let mut prims = Vec::new();
    for name in children(&*data, &root, "primChildren") {
        prims.push(prim(&*data, "", &name, 0)?);
    }
    let time = |name: &str| match field(&*data, &root, name) {
        Some(v) => number(&v).map(|x| (x, NOWHERE)),
        None => None,
    };
    Ok(Layer {
        up_axis,
        times: LayerTimes {
            time_codes_per_second: time("timeCodesPerSecond"),
            frames_per_second: time("framesPerSecond"),
            start_time_code: time("startTimeCode"),
            end_time_code: time("endTimeCode"),
        },
        prims,
    })
}

/// A number field's value; None for a value of another kind.
fn number(v: &sdf::Value) -> Option<f64> {
    match value(v) {
        Value::Number(x) => Some(x),
        _ => None,
    }
}

/// The time samples of the property at `path`, sorted by time, a time written twice read at
/// its last value (as the text reader does); empty when it has none.
fn samples(data: &dyn AbstractData, path: &sdf::Path) -> Vec<Sample> {
    let Some(sdf::Value::TimeSamples(map)) = field(data, path, "timeSamples") else {
        return Vec::new();
    };
    let mut out: Vec<Sample> = map
        .iter()
        .map(|(time, v)| Sample {
            time: *time,
            value: value(v),
            at: NOWHERE,
        })
        .collect();
    // A stable sort keeps samples of one time in the order written; of each run, the last
    // stays.
    out.sort_by(|a, b| a.time.total_cmp(&b.time));
    out.reverse();
    out.dedup_by(|later, kept| later.time.total_cmp(&kept.time).is_eq());
    out.reverse();
    out
}

fn field(data: &dyn AbstractData, path: &sdf::Path, name: &str) -> Option<sdf::Value> {
    data.try_field(path, name)
        .ok()
        .flatten()
        .map(|v| v.into_owned())
}

fn has(data: &dyn AbstractData, path: &sdf::Path, name: &str) -> bool {
    match field(data, path, name) {
        None => false,
        Some(sdf::Value::TokenVec(v)) => !v.is_empty(),
        Some(sdf::Value::PathVec(v)) => !v.is_empty(),
        Some(_) => true,
    }
}

/// The names listed in `path`'s field `name` (`primChildren`, `propertyChildren`).
fn children(data: &dyn AbstractData, path: &sdf::Path, name: &str) -> Vec<String> {
    match field(data, path, name) {
        Some(sdf::Value::TokenVec(names)) => names.iter().map(|t| t.as_ref().to_string()).collect(),
        _ => Vec::new(),
    }
}

/// The prim `name` under the prim at `parent` (`""` at the root).
fn prim(data: &dyn AbstractData, parent: &str, name: &str, depth: usize) -> Result<Prim, String> {
    let shown = format!("{parent}/{name}");
    if depth > MAX_DEPTH {
        return Err(format!("{shown}: prims nest more than {MAX_DEPTH} deep"));
    }
    let path = sdf::Path::from(shown.as_str());
    // A prim spec that writes no specifier is an `over`: that is the field's fallback in USD's
    // schema, and what an empty `over` reads as.
    if !matches!(
        field(data, &path, "specifier"),
        Some(sdf::Value::Specifier(Specifier::Def))
    ) {
        return Err(format!("{shown}: `over` and `class` prims compose opinions from other prims or layers, which glint does not read; flatten the stage (usdcat --flatten) and export again"));
    }
    for (field_name, what) in COMPOSITION_FIELDS {
        if has(data, &path, field_name) {
            return Err(format!("{shown} has {what}, a composition glint does not follow; flatten the stage into one layer (usdcat --flatten in.usd -o flat.usda)"));
        }
    }
    let type_name = match field(data, &path, "typeName") {
        Some(sdf::Value::Token(t)) if !t.as_ref().is_empty() => Some(t.as_ref().to_string()),
        _ => None,
    };
    let inactive = matches!(field(data, &path, "active"), Some(sdf::Value::Bool(false)));
    let mut properties = Vec::new();
    for property_name in children(data, &path, "propertyChildren") {
        let property_path = sdf::Path::from(format!("{shown}.{property_name}").as_str());
        if has(data, &property_path, "spline") {
            return Err(format!("{shown}: `{property_name}` is animated by a spline; glint reads time samples, not splines (export the animation baked to time samples)"));
        }
        let relationship = data.spec_type(&property_path) == Some(SpecType::Relationship);
        let mut type_name = if relationship {
            "rel".to_string()
        } else {
            match field(data, &property_path, "typeName") {
                Some(sdf::Value::Token(t)) => t.as_ref().to_string(),
                _ => String::new(),
            }
        };
        if has(data, &property_path, "connectionPaths") {
            type_name.push_str(".connect");
        }
        properties.push(Property {
            name: property_name,
            type_name,
            default: field(data, &property_path, "default").map(|v| value(&v)),
            samples: samples(data, &property_path),
            at: NOWHERE,
        });
    }
    let mut children_prims = Vec::new();
    for child in children(data, &path, "primChildren") {
        children_prims.push(prim(data, &shown, &child, depth + 1)?);
    }
    Ok(Prim {
        type_name,
        name: name.to_string(),
        at: NOWHERE,
        inactive,
        properties,
        children: children_prims,
    })
}

/// A binary value as the text reader would have read it.
fn value(v: &sdf::Value) -> Value {
    let n = |x: f64| Value::Number(x);
    let list = |items: Vec<Value>| Value::List(items);
    let tuple = |xs: &[f64]| Value::Tuple(xs.iter().map(|&x| Value::Number(x)).collect());
    use sdf::Value as V;
    match v {
        V::Int(x) => n(f64::from(*x)),
        V::Uint(x) => n(f64::from(*x)),
        V::Int64(x) => n(*x as f64),
        V::Uint64(x) => n(*x as f64),
        V::Half(x) => n(f64::from(x.to_f32())),
        V::Float(x) => n(f64::from(*x)),
        V::Double(x) => n(*x),
        V::String(s) => Value::Str(s.clone()),
        V::Token(t) => Value::Str(t.as_ref().to_string()),
        V::TokenVec(ts) => list(
            ts.iter()
                .map(|t| Value::Str(t.as_ref().to_string()))
                .collect(),
        ),
        V::StringVec(ss) => list(ss.iter().map(|s| Value::Str(s.clone())).collect()),
        V::IntVec(xs) => list(xs.iter().map(|&x| n(f64::from(x))).collect()),
        V::FloatVec(xs) => list(xs.iter().map(|&x| n(f64::from(x))).collect()),
        V::DoubleVec(xs) => list(xs.iter().map(|&x| n(x)).collect()),
        V::Vec2d(p) => tuple(&[p.x, p.y]),
        V::Vec2f(p) => tuple(&[f64::from(p.x), f64::from(p.y)]),
        V::Vec3d(p) => tuple(&[p.x, p.y, p.z]),
        V::Vec3f(p) => tuple(&[f64::from(p.x), f64::from(p.y), f64::from(p.z)]),
        V::Vec3h(p) => tuple(&[p.x, p.y, p.z].map(|x| f64::from(x.to_f32()))),
        V::Vec2dVec(ps) => list(ps.iter().map(|p| tuple(&[p.x, p.y])).collect()),
        V::Vec3dVec(ps) => list(ps.iter().map(|p| tuple(&[p.x, p.y, p.z])).collect()),
        V::Vec3fVec(ps) => list(
            ps.iter()
                .map(|p| tuple(&[f64::from(p.x), f64::from(p.y), f64::from(p.z)]))
                .collect(),
        ),
        V::Quatd(q) => tuple(&[q.w, q.x, q.y, q.z]),
        V::Quath(q) => tuple(&[q.w, q.x, q.y, q.z].map(|x| f64::from(x.to_f32()))),
        V::Quatf(q) => tuple(&[
            f64::from(q.w),
            f64::from(q.x),
            f64::from(q.y),
            f64::from(q.z),
        ]),
        V::Matrix4d(m) => Value::Tuple(m.0.chunks(4).map(tuple).collect()),
        _ => Value::Other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use openusd::sdf::{Data, Value as V};
    use openusd::tf::Token;

    /// A `def` prim of `type_name` at `path` in `data`, listed among its parent's children.
    fn def(data: &mut Data, path: &str, type_name: &str) {
        let (parent, name) = path.rsplit_once('/').unwrap();
        let parent = if parent.is_empty() { "/" } else { parent };
        if !data.has_spec(&sdf::Path::from(parent)) {
            data.create_spec(sdf::Path::from(parent), SpecType::PseudoRoot);
        }
        list_under(data, parent, "primChildren", name);
        let at = sdf::Path::from(path);
        data.create_spec(at.clone(), SpecType::Prim);
        data.set_field(&at, "specifier", V::Specifier(Specifier::Def));
        data.set_field(&at, "typeName", V::Token(Token::from(type_name)));
    }

    /// Adds `name` to the token list `field` of the spec at `path`.
    fn list_under(data: &mut Data, path: &str, field_name: &str, name: &str) {
        let at = sdf::Path::from(path);
        let mut names = match field(data, &at, field_name) {
            Some(V::TokenVec(names)) => names,
            _ => Vec::new(),
        };
        names.push(Token::from(name));
        data.set_field(&at, field_name, V::TokenVec(names));
    }

    /// A property `name` of the prim at `prim`: a relationship, or an attribute of
    /// `type_name` holding `default`.
    fn property(data: &mut Data, prim: &str, name: &str, spec: SpecType, type_name: &str) {
        list_under(data, prim, "propertyChildren", name);
        let at = sdf::Path::from(format!("{prim}.{name}").as_str());
        data.create_spec(at.clone(), spec);
        if spec == SpecType::Attribute {
            data.set_field(&at, "typeName", V::Token(Token::from(type_name)));
            data.set_field(&at, "default", V::Double(0.5));
        }
    }

    fn read_prim(data: &Data, name: &str) -> Result<Prim, String> {
        prim(data, "", name, 0)
    }

    #[test]
    fn a_composition_field_is_refused_when_it_lists_something_and_read_past_when_empty() {
        for (field_name, listed, empty) in [
            (
                "variantSetNames",
                V::TokenVec(vec![Token::from("look")]),
                V::TokenVec(Vec::new()),
            ),
            (
                "inheritPaths",
                V::PathVec(vec![sdf::Path::from("/base")]),
                V::PathVec(Vec::new()),
            ),
        ] {
            let mut data = Data::new();
            def(&mut data, "/car", "Xform");
            let at = sdf::Path::from("/car");
            data.set_field(&at, field_name, empty);
            assert!(read_prim(&data, "car").is_ok(), "{field_name} empty");
            data.set_field(&at, field_name, listed);
            let refused = read_prim(&data, "car").unwrap_err();
            assert!(
                refused.starts_with("/car has ") && refused.contains("flatten"),
                "{field_name}: {refused}"
            );
        }
    }

    #[test]
    fn properties_keep_their_written_types_and_a_relationship_reads_as_rel() {
        let mut data = Data::new();
        def(&mut data, "/car", "Xform");
        property(&mut data, "/car", "width", SpecType::Attribute, "double");
        property(
            &mut data,
            "/car",
            "material:binding",
            SpecType::Relationship,
            "",
        );
        property(&mut data, "/car", "tint", SpecType::Attribute, "color3f");
        let tint = sdf::Path::from("/car.tint");
        data.set_field(
            &tint,
            "connectionPaths",
            V::PathVec(vec![sdf::Path::from("/x.y")]),
        );
        let car = read_prim(&data, "car").unwrap();
        assert_eq!(car.type_name.as_deref(), Some("Xform"));
        let types: Vec<(&str, &str)> = car
            .properties
            .iter()
            .map(|p| (p.name.as_str(), p.type_name.as_str()))
            .collect();
        assert_eq!(
            types,
            [
                ("width", "double"),
                ("material:binding", "rel"),
                ("tint", "color3f.connect")
            ]
        );
        assert_eq!(car.properties[0].default, Some(Value::Number(0.5)));
    }

    #[test]
    fn every_integer_and_float_kind_reads_as_its_number() {
        for (written, expected) in [
            (V::Int(-7), -7.0),
            (V::Uint(7), 7.0),
            (V::Int64(-1 << 40), -(2f64.powi(40))),
            (V::Uint64(1 << 40), 2f64.powi(40)),
            (V::Float(0.25), 0.25),
            (V::Double(-0.125), -0.125),
        ] {
            assert_eq!(number(&written), Some(expected), "{written:?}");
        }
    }

    #[test]
    fn every_kind_glint_reads_is_read_as_the_text_reader_reads_it() {
        use openusd::gf::{self, f16};
        let h = f16::from_f32;
        let (num, s) = (Value::Number, |x: &str| Value::Str(x.to_string()));
        let tuple = |xs: &[f64]| Value::Tuple(xs.iter().map(|&x| num(x)).collect());
        let cases: Vec<(V, Value)> = vec![
            (V::Half(h(-0.5)), num(-0.5)),
            (V::String("paint".into()), s("paint")),
            (V::Token(Token::from("Z")), s("Z")),
            (
                V::TokenVec(vec![Token::from("a"), Token::from("b")]),
                Value::List(vec![s("a"), s("b")]),
            ),
            (
                V::StringVec(vec!["c".into(), "d".into()]),
                Value::List(vec![s("c"), s("d")]),
            ),
            (
                V::IntVec(vec![3, -4]),
                Value::List(vec![num(3.0), num(-4.0)]),
            ),
            (V::FloatVec(vec![0.25]), Value::List(vec![num(0.25)])),
            (
                V::DoubleVec(vec![-1.5, 2.0]),
                Value::List(vec![num(-1.5), num(2.0)]),
            ),
            (V::Vec2d([1.0, 2.0].into()), tuple(&[1.0, 2.0])),
            (V::Vec2f([3.0, 4.0].into()), tuple(&[3.0, 4.0])),
            (V::Vec3d([1.0, 2.0, 3.0].into()), tuple(&[1.0, 2.0, 3.0])),
            (V::Vec3f([4.0, 5.0, 6.0].into()), tuple(&[4.0, 5.0, 6.0])),
            (
                V::Vec3h([h(0.5), h(1.0), h(2.0)].into()),
                tuple(&[0.5, 1.0, 2.0]),
            ),
            (
                V::Vec2dVec(vec![[0.0, 1.0].into(), [2.0, 3.0].into()]),
                Value::List(vec![tuple(&[0.0, 1.0]), tuple(&[2.0, 3.0])]),
            ),
            (
                V::Vec3dVec(vec![[0.0, 1.0, 2.0].into()]),
                Value::List(vec![tuple(&[0.0, 1.0, 2.0])]),
            ),
            (
                V::Vec3fVec(vec![[3.0, 4.0, 5.0].into()]),
                Value::List(vec![tuple(&[3.0, 4.0, 5.0])]),
            ),
            (
                V::Quatd(gf::Quatd {
                    w: 1.0,
                    x: 2.0,
                    y: 3.0,
                    z: 4.0,
                }),
                tuple(&[1.0, 2.0, 3.0, 4.0]),
            ),
            (
                V::Quatf(gf::Quatf {
                    w: 0.5,
                    x: 1.0,
                    y: 1.5,
                    z: 2.0,
                }),
                tuple(&[0.5, 1.0, 1.5, 2.0]),
            ),
            (
                V::Quath(gf::Quath {
                    w: h(2.0),
                    x: h(0.5),
                    y: h(0.25),
                    z: h(1.0),
                }),
                tuple(&[2.0, 0.5, 0.25, 1.0]),
            ),
            (
                V::Matrix4d(gf::Matrix4d(std::array::from_fn(|k| k as f64))),
                Value::Tuple(
                    (0..4)
                        .map(|r| tuple(&[0.0, 1.0, 2.0, 3.0].map(|c| c + 4.0 * f64::from(r))))
                        .collect(),
                ),
            ),
            (V::Bool(true), Value::Other),
        ];
        for (written, expected) in cases {
            assert_eq!(value(&written), expected, "{written:?}");
        }
    }

    #[test]
    fn prims_nest_as_deep_as_the_limit_and_no_deeper() {
        // Each level of the reader's recursion takes a frame of its own: a thread with room.
        let nest = |levels: usize| {
            std::thread::Builder::new()
                .stack_size(256 << 20)
                .spawn(move || {
                    let mut data = Data::new();
                    let mut path = String::new();
                    for level in 0..levels {
                        path.push_str(&format!("/p{level}"));
                        def(&mut data, &path, "Xform");
                    }
                    read_prim(&data, "p0").map(|_| ())
                })
                .unwrap()
                .join()
                .unwrap()
        };
        assert_eq!(nest(MAX_DEPTH + 1), Ok(()));
        let refused = nest(MAX_DEPTH + 2).unwrap_err();
        assert!(
            refused.ends_with(&format!("prims nest more than {MAX_DEPTH} deep")),
            "{refused}"
        );
    }
}
