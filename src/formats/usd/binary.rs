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
