//! The map in Reuleaux's HDF5 layout, so its RViz plugins and scripts open it:
//! `/Spheres/sphere_dataset` (S×4 float64: centre x, y, z and the reachability index, an
//! attribute `Resolution`, float32) and `/Poses/poses_dataset` (P×10 float32: centre,
//! pose position, quaternion x, y, z, w; Reuleaux's 50 poses only), as its map creator
//! writes them; kinegen's measures beside them in `/kinegen` (the `.npz` arrays).

use hdf5_pure::{AttrValue, FileBuilder};

use super::map::Map;
use super::npz::Array;

/// The file's bytes.
pub fn bytes(map: &Map) -> Result<Vec<u8>, String> {
    let mut fb = FileBuilder::new();
    let mut measures = fb.create_group("kinegen");
    let shape = |s: &[usize]| s.iter().map(|&d| d as u64).collect::<Vec<_>>();
    for (name, array) in map.arrays() {
        match (name, array) {
            ("spheres", Array::F64(s, data)) => {
                let mut g = fb.create_group("Spheres");
                g.create_dataset("sphere_dataset")
                    .with_f64_data(&data)
                    .with_shape(&shape(&s))
                    .set_attr(
                        "Resolution",
                        AttrValue::F32(map.settings.grid.resolution as f32),
                    );
                fb.add_group(g.finish());
            }
            ("poses", Array::F32(s, data)) => {
                let mut g = fb.create_group("Poses");
                g.create_dataset("poses_dataset")
                    .with_f32_data(&data)
                    .with_shape(&shape(&s));
                fb.add_group(g.finish());
            }
            (name, Array::F64(s, data)) => {
                // A scalar (the resolution) as one element.
                let s = if s.is_empty() { vec![1] } else { s };
                measures
                    .create_dataset(name)
                    .with_f64_data(&data)
                    .with_shape(&shape(&s));
            }
            (name, Array::F32(s, data)) => {
                measures
                    .create_dataset(name)
                    .with_f32_data(&data)
                    .with_shape(&shape(&s));
            }
            (name, Array::U32(s, data)) => {
                measures
                    .create_dataset(name)
                    .with_u32_data(&data)
                    .with_shape(&shape(&s));
            }
            (name, Array::Str(v)) => {
                let v: Vec<&str> = v.iter().map(String::as_str).collect();
                // An empty list (no singular factor) has no string width: left out.
                if !v.is_empty() {
                    measures
                        .create_dataset(name)
                        .with_strings(&v)
                        .map_err(|e| e.to_string())?;
                }
            }
        }
    }
    fb.add_group(measures.finish());
    fb.finish().map_err(|e| e.to_string())
}
