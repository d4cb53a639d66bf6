//! The binary part of a glTF file: one buffer, a buffer view per accessor.

use serde_json::{Value, json};

/// `ARRAY_BUFFER`: vertex attributes.
const VERTICES: u32 = 34962;
/// `ELEMENT_ARRAY_BUFFER`: indices.
const INDICES: u32 = 34963;
/// Component types.
const FLOAT: u32 = 5126;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_BYTE: u32 = 5121;

/// `x` rounded to 7 decimals, as an `f32` for the buffer: every computed float of the
/// buffer goes through it, so that the last bit of a platform's `sin` or `cos` cannot change
/// the file.
pub fn quantize(x: f64) -> f32 {
    ((x * 1e7).round() / 1e7) as f32
}

/// `x` rounded to 9 decimals, for the JSON (which holds `f64`s): as [`quantize`].
pub fn quantize_json(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}

/// The buffer, its views and accessors, as they are appended.
#[derive(Default)]
pub struct Buffers {
    pub bytes: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
}

impl Buffers {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        let mut view = json!({
            "buffer": 0,
            "byteOffset": self.bytes.len(),
            "byteLength": bytes.len(),
        });
        if let Some(target) = target {
            view["target"] = json!(target);
        }
        self.bytes.extend_from_slice(bytes);
        self.views.push(view);
        self.views.len() - 1
    }

    fn accessor(&mut self, accessor: Value) -> usize {
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// A float accessor of `N`-component elements (`N` 1, 2, 3, 4 or 16), with its `min`
    /// and `max` (which glTF requires of positions and animation inputs).
    fn floats<const N: usize>(&mut self, data: &[[f32; N]], target: Option<u32>) -> usize {
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let view = self.view(&bytes, target);
        let kind = match N {
            1 => "SCALAR",
            2 => "VEC2",
            3 => "VEC3",
            4 => "VEC4",
            16 => "MAT4",
            _ => unreachable!("{N} components"),
        };
        let mut accessor = json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": data.len(),
            "type": kind,
        });
        if N <= 4 {
            let bound = |pick: fn(f32, f32) -> f32| -> Vec<f32> {
                (0..N)
                    .map(|i| data.iter().map(|e| e[i]).reduce(pick).unwrap_or(0.0))
                    .collect()
            };
            accessor["min"] = json!(bound(f32::min));
            accessor["max"] = json!(bound(f32::max));
        }
        self.accessor(accessor)
    }

    /// A vertex attribute of floats.
    pub fn attribute<const N: usize>(&mut self, data: &[[f32; N]]) -> usize {
        self.floats(data, Some(VERTICES))
    }

    /// Floats that are no vertex attribute: animation keyframes, inverse bind matrices.
    pub fn data<const N: usize>(&mut self, data: &[[f32; N]]) -> usize {
        self.floats(data, None)
    }

    /// Triangle indices.
    pub fn indices(&mut self, data: &[u16]) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = self.view(&bytes, Some(INDICES));
        self.accessor(json!({
            "bufferView": view,
            "componentType": UNSIGNED_SHORT,
            "count": data.len(),
            "type": "SCALAR",
        }))
    }

    /// `JOINTS_0`: four joint indices per vertex.
    pub fn joints(&mut self, data: &[[u8; 4]]) -> usize {
        let view = self.view(data.as_flattened(), Some(VERTICES));
        self.accessor(json!({
            "bufferView": view,
            "componentType": UNSIGNED_BYTE,
            "count": data.len(),
            "type": "VEC4",
        }))
    }
}
