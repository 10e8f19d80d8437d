//! Structure-aware mutations: each loader's input is taken apart into its structure (JSON
//! values, GLB and PNG chunks, OBJ/MTL/TOML lines), mutated there (numbers made huge or
//! hostile, elements duplicated or reordered, references made cyclic, repeated or pointed out
//! of the folder, counts inflated), then put back together and optionally truncated or
//! byte-flipped. A mutation is `(op, a, b)`: `op` chooses what, `a` and `b` where and how.

use serde_json::Value;

/// One mutation step.
pub type Step = (u8, u64, u64);

/// Numbers a hostile file puts where counts, offsets, indices and factors go.
const HOSTILE_NUMBERS: [f64; 10] =
    [0.0, -1.0, 1e300, -1e300, 4294967295.0, 9007199254740992.0, 1e-45, 3.0, 65536.0, 1e9];
/// Paths a hostile file references.
pub const HOSTILE_PATHS: [&str; 7] =
    ["/dev/zero", "../outside.bin", "/etc/hostname", "a.gltf", "sub/../../x", ".", "data:x"];

fn pick<T: Copy>(items: &[T], r: u64) -> T {
    items[(r % items.len() as u64) as usize]
}

/// Every JSON pointer in `v` whose value satisfies `f`.
fn pointers(v: &Value, at: String, f: &dyn Fn(&Value) -> bool, out: &mut Vec<String>) {
    if f(v) {
        out.push(at.clone());
    }
    match v {
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                pointers(x, format!("{at}/{i}"), f, out);
            }
        }
        Value::Object(o) => {
            for (k, x) in o {
                pointers(x, format!("{at}/{k}"), f, out);
            }
        }
        _ => {}
    }
}

fn pointer_where(v: &Value, r: u64, f: &dyn Fn(&Value) -> bool) -> Option<String> {
    let mut all = Vec::new();
    pointers(v, String::new(), f, &mut all);
    (!all.is_empty()).then(|| all[(r % all.len() as u64) as usize].clone())
}

/// Mutates a glTF JSON document in place (one step).
pub fn json_step(doc: &mut Value, (op, a, b): Step) {
    match op % 8 {
        0 => {
            if let Some(p) = pointer_where(doc, a, &|v| v.is_number()) {
                let n = pick(&HOSTILE_NUMBERS, b);
                *doc.pointer_mut(&p).unwrap() = serde_json::json!(n);
            }
        }
        1 => {
            // Duplicate an array element (repeated references, repeated children).
            if let Some(p) = pointer_where(doc, a, &|v| v.as_array().is_some_and(|x| !x.is_empty()))
            {
                let arr = doc.pointer_mut(&p).unwrap().as_array_mut().unwrap();
                let x = arr[(b % arr.len() as u64) as usize].clone();
                arr.insert((b / 7 % (arr.len() as u64 + 1)) as usize, x);
            }
        }
        2 => {
            // Reorder an array (indices now point at other elements).
            if let Some(p) = pointer_where(doc, a, &|v| v.as_array().is_some_and(|x| x.len() > 1)) {
                let arr = doc.pointer_mut(&p).unwrap().as_array_mut().unwrap();
                let k = (b % arr.len() as u64) as usize;
                arr.rotate_left(k.max(1));
            }
        }
        3 => {
            if let Some(p) =
                pointer_where(doc, a, &|v| v.as_object().is_some_and(|o| !o.is_empty()))
            {
                let obj = doc.pointer_mut(&p).unwrap().as_object_mut().unwrap();
                let key = obj.keys().nth((b % obj.len() as u64) as usize).unwrap().clone();
                obj.remove(&key);
            }
        }
        4 => {
            // Node children pointing anywhere: cycles, DAGs, repeats, out of range.
            if let Some(nodes) = doc.get_mut("nodes").and_then(Value::as_array_mut) {
                let n = nodes.len().max(1) as u64;
                let i = (a % n) as usize;
                let kids: Vec<u64> = [b % (n + 1), (b >> 8) % (n + 1), (b >> 16) % (n + 1)]
                    [..(1 + (b >> 24) % 3) as usize]
                    .to_vec();
                if let Some(node) = nodes.get_mut(i).and_then(Value::as_object_mut) {
                    node.insert("children".into(), serde_json::json!(kids));
                }
                if b >> 40 & 1 == 1 {
                    nodes.push(serde_json::json!({"mesh": 0, "children": [a % n]}));
                }
            }
        }
        5 => {
            // Counts and lengths inflated.
            let key = pick(&["count", "byteLength", "byteOffset", "byteStride"], b);
            if let Some(p) = pointer_where(doc, a, &|v| v.get(key).is_some()) {
                let big = pick(&[1u64 << 20, 1 << 26, 1 << 31, u32::MAX as u64, 3], b >> 8);
                doc.pointer_mut(&p).unwrap()[key] = serde_json::json!(big);
            }
        }
        6 => {
            // A URI made hostile.
            if let Some(p) = pointer_where(doc, a, &|v| v.get("uri").is_some()) {
                doc.pointer_mut(&p).unwrap()["uri"] = serde_json::json!(pick(&HOSTILE_PATHS, b));
            }
        }
        _ => {
            // An accessor without a buffer view, or a normalised one.
            if let Some(p) = pointer_where(doc, a, &|v| v.get("componentType").is_some()) {
                let acc = doc.pointer_mut(&p).unwrap().as_object_mut().unwrap();
                if b & 1 == 0 {
                    acc.remove("bufferView");
                } else {
                    acc.insert("normalized".into(), Value::Bool(true));
                }
            }
        }
    }
}

/// Byte-level finish: truncation (op 0) or flips (op 1); other ops leave the bytes.
pub fn bytes_step(v: &mut Vec<u8>, (op, a, b): Step) {
    if v.is_empty() {
        return;
    }
    match op % 4 {
        0 => v.truncate((a % v.len() as u64) as usize),
        1 => {
            let i = (a % v.len() as u64) as usize;
            v[i] ^= (b as u8).max(1);
        }
        _ => {}
    }
}

/// Mutates a text file line by line (OBJ, MTL, TOML): `extra` are hostile lines it may insert.
pub fn lines_step(lines: &mut Vec<String>, (op, a, b): Step, extra: &[&str]) {
    let n = lines.len().max(1) as u64;
    let i = (a % n) as usize;
    match op % 6 {
        0 if !lines.is_empty() => {
            let l = lines[i].clone();
            lines.insert((b % (n + 1)) as usize, l);
        }
        1 if !lines.is_empty() => {
            lines.remove(i);
        }
        2 if lines.len() > 1 => {
            let j = (b % n) as usize;
            lines.swap(i, j);
        }
        3 if !lines.is_empty() => {
            // A number replaced by a hostile one.
            let words: Vec<String> = lines[i].split(' ').map(str::to_owned).collect();
            let nums: Vec<usize> =
                (0..words.len()).filter(|&k| words[k].parse::<f64>().is_ok()).collect();
            if !nums.is_empty() {
                let mut words = words;
                let k = nums[(b % nums.len() as u64) as usize];
                words[k] = pick(
                    &["nan", "inf", "-1", "1e30", "2147483648", "0", "-0", "99999999999", "1e-40"],
                    b >> 8,
                )
                .to_owned();
                lines[i] = words.join(" ");
            }
        }
        4 if !extra.is_empty() => {
            let l = pick(extra, b).to_owned();
            lines.insert((a % (lines.len() as u64 + 1)) as usize, l);
        }
        _ => {}
    }
}

/// PNG chunks: `(type, data)` after the 8-byte signature; `None` if not a PNG.
pub fn png_chunks(b: &[u8]) -> Option<Vec<([u8; 4], Vec<u8>)>> {
    let mut out = Vec::new();
    let mut i = 8;
    while i + 12 <= b.len() {
        let len = u32::from_be_bytes(b[i..i + 4].try_into().unwrap()) as usize;
        let ty: [u8; 4] = b[i + 4..i + 8].try_into().unwrap();
        let data = b.get(i + 8..i + 8 + len)?.to_vec();
        out.push((ty, data));
        i += 12 + len;
    }
    Some(out)
}

/// Chunks back into a PNG with valid CRCs (so the mutation reaches the decoder's logic).
pub fn png_join(chunks: &[([u8; 4], Vec<u8>)]) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    for (ty, data) in chunks {
        out.extend_from_slice(&(data.len() as u32).to_be_bytes());
        out.extend_from_slice(ty);
        out.extend_from_slice(data);
        let crc = crc32(ty.iter().chain(data));
        out.extend_from_slice(&crc.to_be_bytes());
    }
    out
}

fn crc32<'a>(bytes: impl Iterator<Item = &'a u8>) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 == 1 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
        }
    }
    !c
}

/// Mutates PNG chunks: the header's size and format, duplicated and reordered chunks,
/// chunk data flipped or truncated.
pub fn png_step(chunks: &mut Vec<([u8; 4], Vec<u8>)>, (op, a, b): Step) {
    if chunks.is_empty() {
        return;
    }
    let n = chunks.len() as u64;
    let i = (a % n) as usize;
    match op % 5 {
        0 => {
            if let Some((_, ihdr)) = chunks.iter_mut().find(|(t, d)| t == b"IHDR" && d.len() >= 13)
            {
                let big = pick(&[1u32, 8192, 16384, 65535, 1 << 20, u32::MAX, 0, 4097], b);
                let at = if a & 1 == 0 { 0 } else { 4 };
                ihdr[at..at + 4].copy_from_slice(&big.to_be_bytes());
                if b >> 8 & 1 == 1 {
                    ihdr[8] = pick(&[1u8, 2, 4, 8, 16, 3], b >> 9); // bit depth
                    ihdr[9] = pick(&[0u8, 2, 3, 4, 6, 7], b >> 12); // colour type
                }
            }
        }
        1 => {
            let c = chunks[i].clone();
            chunks.insert((b % (n + 1)) as usize, c);
        }
        2 => {
            let j = (b % n) as usize;
            chunks.swap(i, j);
        }
        3 => {
            let d = &mut chunks[i].1;
            if !d.is_empty() {
                let k = (b % d.len() as u64) as usize;
                d[k] ^= ((b >> 32) as u8).max(1);
            }
        }
        _ => {
            let d = &mut chunks[i].1;
            d.truncate((b % (d.len() as u64 + 1)) as usize);
        }
    }
}

/// GLB chunks: `(type, data)` after the 12-byte header; `None` if not a GLB.
pub fn glb_chunks(b: &[u8]) -> Option<Vec<(u32, Vec<u8>)>> {
    let mut out = Vec::new();
    let mut i = 12;
    while i + 8 <= b.len() {
        let len = u32::from_le_bytes(b[i..i + 4].try_into().unwrap()) as usize;
        let ty = u32::from_le_bytes(b[i + 4..i + 8].try_into().unwrap());
        out.push((ty, b.get(i + 8..i + 8 + len)?.to_vec()));
        i += 8 + len;
    }
    Some(out)
}

/// Chunks back into a GLB; `total` overrides the header's length field.
pub fn glb_join(chunks: &[(u32, Vec<u8>)], total: Option<u32>) -> Vec<u8> {
    let len: usize = 12 + chunks.iter().map(|(_, d)| 8 + d.len()).sum::<usize>();
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.unwrap_or(len as u32).to_le_bytes());
    for (ty, d) in chunks {
        out.extend_from_slice(&(d.len() as u32).to_le_bytes());
        out.extend_from_slice(&ty.to_le_bytes());
        out.extend_from_slice(d);
    }
    out
}

/// Mutates GLB chunks: duplicated, reordered, retyped, or the JSON chunk mutated as JSON.
pub fn glb_step(chunks: &mut Vec<(u32, Vec<u8>)>, total: &mut Option<u32>, step: Step) {
    let (op, a, b) = step;
    if chunks.is_empty() {
        return;
    }
    let n = chunks.len() as u64;
    let i = (a % n) as usize;
    match op % 5 {
        0 => {
            let c = chunks[i].clone();
            chunks.insert((b % (n + 1)) as usize, c);
        }
        1 => {
            let j = (b % n) as usize;
            chunks.swap(i, j);
        }
        2 => chunks[i].0 = pick(&[0x4E4F_534A, 0x004E_4942, 0, u32::MAX], b),
        3 => *total = Some(pick(&[0, 12, u32::MAX, 1 << 30], b)),
        _ => {
            if let Some((_, json)) = chunks.iter_mut().find(|(t, _)| *t == 0x4E4F_534A)
                && let Ok(mut doc) = serde_json::from_slice::<Value>(json)
            {
                json_step(&mut doc, ((b % 8) as u8, a, b >> 3));
                let mut text = serde_json::to_vec(&doc).unwrap();
                while !text.len().is_multiple_of(4) {
                    text.push(b' ');
                }
                *json = text;
            }
        }
    }
}
