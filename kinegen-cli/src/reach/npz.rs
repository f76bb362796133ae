//! NumPy's `.npz`: a zip of `.npy` arrays (format 1.0, little-endian, C order), what
//! `numpy.load` opens. Written uncompressed, so a map of millions of voxels is written
//! at disk speed.

use std::io::{Read, Write};

/// One array of the file.
#[derive(Clone, Debug, PartialEq)]
pub enum Array {
    /// `float64` of a shape.
    F64(Vec<usize>, Vec<f64>),
    /// `float32` of a shape.
    F32(Vec<usize>, Vec<f32>),
    /// `uint32` of a shape.
    U32(Vec<usize>, Vec<u32>),
    /// A 1-D array of unicode strings (`<U{longest}`).
    Str(Vec<String>),
}

impl Array {
    fn header(&self) -> (String, Vec<usize>) {
        match self {
            Array::F64(s, _) => ("<f8".into(), s.clone()),
            Array::F32(s, _) => ("<f4".into(), s.clone()),
            Array::U32(s, _) => ("<u4".into(), s.clone()),
            Array::Str(v) => {
                let longest = v.iter().map(|s| s.chars().count()).max().unwrap_or(0);
                (format!("<U{}", longest.max(1)), vec![v.len()])
            }
        }
    }

    /// The `.npy` bytes.
    fn npy(&self) -> Vec<u8> {
        let (descr, shape) = self.header();
        let shape = match shape.len() {
            1 => format!("({},)", shape[0]),
            _ => format!(
                "({})",
                shape
                    .iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        let mut dict =
            format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
        // Magic (6) + version (2) + length (2) + dict + '\n', a multiple of 64.
        while (10 + dict.len() + 1) % 64 != 0 {
            dict.push(' ');
        }
        dict.push('\n');
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        out.extend((dict.len() as u16).to_le_bytes());
        out.extend(dict.as_bytes());
        match self {
            Array::F64(_, d) => d.iter().for_each(|x| out.extend(x.to_le_bytes())),
            Array::F32(_, d) => d.iter().for_each(|x| out.extend(x.to_le_bytes())),
            Array::U32(_, d) => d.iter().for_each(|x| out.extend(x.to_le_bytes())),
            Array::Str(v) => {
                let width: usize = descr[2..].parse().unwrap_or(1);
                for s in v {
                    let mut n = 0;
                    for c in s.chars() {
                        out.extend((c as u32).to_le_bytes());
                        n += 1;
                    }
                    for _ in n..width {
                        out.extend(0u32.to_le_bytes());
                    }
                }
            }
        }
        out
    }
}

/// Write `arrays` as an `.npz` to `w` (`name.npy` entries, in this order).
pub fn write<W: Write + std::io::Seek>(
    w: W,
    arrays: &[(&str, Array)],
) -> zip::result::ZipResult<W> {
    let mut zip = zip::ZipWriter::new(w);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .large_file(true);
    for (name, array) in arrays {
        zip.start_file(format!("{name}.npy"), options)?;
        zip.write_all(&array.npy())?;
    }
    zip.finish()
}

/// The arrays of an `.npz` that [`write()`] wrote, by name (for tests and tools reading
/// a map back).
pub fn read<R: Read + std::io::Seek>(r: R) -> Result<Vec<(String, Array)>, String> {
    let mut zip = zip::ZipArchive::new(r).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    for i in 0..zip.len() {
        let mut f = zip.by_index(i).map_err(|e| e.to_string())?;
        let name = f.name().map_err(|e| e.to_string())?;
        let name = name.trim_end_matches(".npy").to_string();
        let mut bytes = Vec::new();
        f.read_to_end(&mut bytes).map_err(|e| e.to_string())?;
        out.push((name, parse_npy(&bytes)?));
    }
    Ok(out)
}

fn parse_npy(b: &[u8]) -> Result<Array, String> {
    if b.len() < 10 || &b[..8] != b"\x93NUMPY\x01\x00" {
        return Err("not an .npy 1.0 array".into());
    }
    let len = u16::from_le_bytes([b[8], b[9]]) as usize;
    let dict = std::str::from_utf8(&b[10..10 + len]).map_err(|e| e.to_string())?;
    let field = |key: &str| -> Result<&str, String> {
        let start = dict.find(key).ok_or(format!("no {key}"))? + key.len();
        Ok(&dict[start..])
    };
    let descr = field("'descr': '")?;
    let descr = &descr[..descr.find('\'').ok_or("bad descr")?];
    let shape = field("'shape': (")?;
    let shape: Vec<usize> = shape[..shape.find(')').ok_or("bad shape")?]
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().map_err(|_| format!("bad shape {s}")))
        .collect::<Result<_, _>>()?;
    let data = &b[10 + len..];
    let words = |n: usize| data.chunks_exact(n);
    Ok(match descr {
        "<f8" => Array::F64(
            shape,
            words(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap_or_default()))
                .collect(),
        ),
        "<f4" => Array::F32(
            shape,
            words(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap_or_default()))
                .collect(),
        ),
        "<u4" => Array::U32(
            shape,
            words(4)
                .map(|c| u32::from_le_bytes(c.try_into().unwrap_or_default()))
                .collect(),
        ),
        d if d.starts_with("<U") => {
            let width: usize = d[2..].parse().map_err(|_| "bad width")?;
            let chars: Vec<char> = words(4)
                .map(|c| u32::from_le_bytes(c.try_into().unwrap_or_default()))
                .map(|u| char::from_u32(u).unwrap_or('\u{fffd}'))
                .collect();
            Array::Str(
                chars
                    .chunks(width)
                    .map(|s| s.iter().filter(|c| **c != '\0').collect())
                    .collect(),
            )
        }
        d => return Err(format!("dtype {d} is not one kinegen writes")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_read_back_equal_and_headers_align() {
        let arrays = vec![
            (
                "a",
                Array::F64(vec![2, 3], vec![1.0, 2.5, -3.0, 4.0, 5.0, 1e-300]),
            ),
            ("b", Array::F32(vec![1, 2], vec![0.5, -0.25])),
            ("c", Array::U32(vec![3], vec![0, 7, u32::MAX])),
            ("d", Array::Str(vec!["sin(q5)".into(), "a2·c2 + a3".into()])),
        ];
        for (_, a) in &arrays {
            let npy = a.npy();
            let len = u16::from_le_bytes([npy[8], npy[9]]) as usize;
            assert_eq!((10 + len) % 64, 0);
        }
        let mut buf = std::io::Cursor::new(Vec::new());
        write(&mut buf, &arrays).unwrap();
        buf.set_position(0);
        let back = read(buf).unwrap();
        let names: Vec<_> = back.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["a", "b", "c", "d"]);
        for ((_, a), (_, b)) in arrays.iter().zip(&back) {
            assert_eq!(a, b);
        }
    }
}
