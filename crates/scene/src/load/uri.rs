//! glTF URIs: `data:` (base64) payloads and files relative to the referencing file, read
//! through the load's [`Ctx`] (confined to the root folder, regular files only, size-capped).

use super::context::Ctx;
use crate::LoadErrorKind;
use std::path::Path;

/// Reads a `data:` URI (base64) or a file relative to `base`.
pub(crate) fn read_uri(
    uri: &str,
    base: Option<&Path>,
    ctx: &Ctx,
) -> Result<Vec<u8>, LoadErrorKind> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let payload = rest
            .split_once(";base64,")
            .map(|(_, d)| d)
            .ok_or_else(|| LoadErrorKind::Unsupported("data URI that is not base64".into()))?;
        return base64(payload)
            .ok_or_else(|| LoadErrorKind::Parse("invalid base64 in data URI".into()));
    }
    if uri.contains("://") {
        return Err(LoadErrorKind::Unsupported(format!("URI scheme of `{uri}`")));
    }
    let base = base.ok_or_else(|| {
        LoadErrorKind::Unsupported(format!("external file `{uri}` in an in-memory load"))
    })?;
    ctx.read(&ctx.resolve(base, &percent_decode(uri))?)
}

fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%'
            && i + 2 < b.len()
            && let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2]))
        {
            out.push((h * 16 + l) as u8);
            i += 3;
            continue;
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Standard base64 (RFC 4648) with optional padding; `None` on any other character.
fn base64(s: &str) -> Option<Vec<u8>> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' | b'-' => Some(62),
        b'/' | b'_' => Some(63),
        _ => None,
    };
    let s = s.trim_end_matches('=');
    let mut out = Vec::with_capacity(s.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0);
    for c in s.bytes() {
        acc = (acc << 6) | val(c)? as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    #[test]
    fn base64_round_trips_known_values() {
        assert_eq!(super::base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(super::base64("AAECAw").unwrap(), [0, 1, 2, 3]);
        assert!(super::base64("a*b").is_none());
    }

    #[test]
    fn percent_decoding_survives_bad_escapes() {
        assert_eq!(super::percent_decode("a%20b"), "a b");
        assert_eq!(super::percent_decode("a%zz%"), "a%zz%");
        assert_eq!(super::percent_decode("%FF"), "\u{fffd}");
    }
}
