//! The JSON request extractor: bounded body, errors naming the JSON path of the bad value.

use crate::ApiError;
use axum::body::Bytes;
use axum::extract::{FromRequest, Request};
use axum::http::StatusCode;
use axum::response::IntoResponse;
use serde::de::DeserializeOwned;

/// A JSON request body decoded into `T`.
///
/// Unlike axum's `Json`, a malformed body answers `400 {"error": "...", "field": "drive.stroke_m"}`
/// with the JSON path of the offending value, and a body over [`crate::MAX_BODY_BYTES`] answers
/// 413. The content type is not checked, so a plain `fetch` with a string body works.
#[derive(Debug, Clone)]
pub struct ApiJson<T>(pub T);

impl<S: Send + Sync, T: DeserializeOwned> FromRequest<S> for ApiJson<T> {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, Self::Rejection> {
        // A body announced larger than the limit is refused at once, before any of it is read (a
        // client announcing 10¹⁵ bytes was otherwise waited for).
        let announced = req.headers().get(axum::http::header::CONTENT_LENGTH).and_then(|v| v.to_str().ok());
        if announced.and_then(|v| v.trim().parse::<u64>().ok()).is_some_and(|n| n > crate::MAX_BODY_BYTES as u64) {
            return Err(ApiError::TooLarge { limit: crate::MAX_BODY_BYTES });
        }
        let timeout = req.extensions().get::<BodyTimeout>().map_or(crate::BODY_READ_TIMEOUT, |t| t.0);
        let read = tokio::time::timeout(timeout, Bytes::from_request(req, state));
        let bytes =
            read.await.map_err(|_| ApiError::Timeout { what: "request body", limit: timeout })?.map_err(|rej| {
                if rej.status() == StatusCode::PAYLOAD_TOO_LARGE {
                    ApiError::TooLarge { limit: crate::MAX_BODY_BYTES }
                } else {
                    ApiError::BadJson { field: "body".into(), message: rej.body_text() }
                }
            })?;
        parse_json(&bytes).map(ApiJson)
    }
}

/// The body read timeout of a server (a request extension; [`crate::BODY_READ_TIMEOUT`] without it).
#[derive(Debug, Clone, Copy)]
pub(crate) struct BodyTimeout(pub(crate) std::time::Duration);

/// Longest message of a JSON error (characters): serde quotes the bad value, which may be a
/// string of 100 000 characters; the middle is cut.
const MAX_MESSAGE_CHARS: usize = 600;

pub(crate) fn cut(text: &str) -> String {
    let n = text.chars().count();
    if n <= MAX_MESSAGE_CHARS {
        return text.to_string();
    }
    let head: String = text.chars().take(MAX_MESSAGE_CHARS / 2).collect();
    let tail: String = text.chars().skip(n - MAX_MESSAGE_CHARS / 2 + 40).collect();
    format!("{head} … ({} characters cut) … {tail}", n - MAX_MESSAGE_CHARS + 40)
}

/// Decodes JSON text, naming the path of the first bad value in the error.
///
/// The text must be one JSON object (`[]` or a bare number is not a request), with nothing but
/// white space after it, and every key must be known at every depth (a misspelt key is refused
/// with its path rather than silently ignored).
pub fn parse_json<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    let bad = |field: String, message: String| ApiError::BadJson { field, message: cut(&message) };
    if bytes.iter().find(|b| !b.is_ascii_whitespace()) != Some(&b'{') {
        return Err(bad("body".into(), "the request body must be one JSON object {…}".into()));
    }
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let mut unknown: Option<String> = None;
    let value = {
        let mut note = |path: serde_ignored::Path<'_>| {
            if unknown.is_none() {
                unknown = Some(path.to_string());
            }
        };
        let ignoring = serde_ignored::Deserializer::new(&mut de, &mut note);
        serde_path_to_error::deserialize(ignoring).map_err(|e| {
            let path = e.path().to_string();
            let field = if path.is_empty() || path == "." || path == "?" { "body".to_string() } else { path };
            bad(field, e.into_inner().to_string())
        })?
    };
    de.end().map_err(|e| bad("body".into(), format!("data after the JSON object ({e})")))?;
    if let Some(path) = unknown {
        let key = path.rsplit('.').next().unwrap_or(&path).to_string();
        return Err(bad(path, format!("unknown field `{key}`")));
    }
    Ok(value)
}

/// Decodes TOML text, naming the path of the first bad value in the error.
///
/// The message is one line: `line L, column C: what is wrong` (the TOML crate's own text
/// draws the line with a caret over several lines).
pub fn parse_toml<T: DeserializeOwned>(text: &str) -> Result<T, ApiError> {
    let de = toml::Deserializer::parse(text)
        .map_err(|e| ApiError::BadJson { field: "text".into(), message: loomkin_units::toml_reason(text, &e) })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let field = if path.is_empty() || path == "." || path == "?" { "text".to_string() } else { path };
        ApiError::BadJson { field, message: loomkin_units::toml_reason(text, &e.into_inner()) }
    })
}

impl<T: serde::Serialize> IntoResponse for ApiJson<T> {
    fn into_response(self) -> axum::response::Response {
        axum::Json(self.0).into_response()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Inner {
        stroke_m: f64,
    }
    #[derive(Debug, Deserialize)]
    #[allow(dead_code)]
    struct Outer {
        drive: Inner,
    }

    #[test]
    fn json_errors_name_the_path() {
        let e = parse_json::<Outer>(br#"{"drive": {"stroke_m": "x"}}"#).unwrap_err();
        assert_eq!(e.field(), "drive.stroke_m");
        let e = parse_json::<Outer>(b"{not json").unwrap_err();
        assert_eq!(e.field(), "body");
        // Trailing data, a non-object body and unknown keys at any depth are refused.
        let e = parse_json::<Outer>(br#"{"drive": {"stroke_m": 1}} this is not json"#).unwrap_err();
        assert!(e.field() == "body" && e.to_string().contains("after the JSON object"), "{e}");
        assert!(parse_json::<Outer>(b"  {\"drive\": {\"stroke_m\": 1}}\n ").is_ok());
        assert_eq!(parse_json::<Outer>(b"[]").unwrap_err().field(), "body");
        let e = parse_json::<Outer>(br#"{"drive": {"stroke_m": 1}, "extra": 2}"#).unwrap_err();
        assert_eq!((e.field(), e.to_string().as_str()), ("extra", "extra: unknown field `extra`"));
        // A huge bad value is not echoed in full.
        let e = parse_json::<Outer>(format!(r#"{{"drive": {{"stroke_m": "{}"}}}}"#, "x".repeat(100_000)).as_bytes());
        let text = e.unwrap_err().to_string();
        assert!(text.chars().count() < 700 && text.contains("characters cut"), "{}", text.len());
    }

    #[test]
    fn toml_errors_name_the_path() {
        let e = parse_toml::<Outer>("[drive]\nstroke_m = \"x\"\n").unwrap_err();
        assert_eq!(e.field(), "drive.stroke_m");
        assert!(parse_toml::<Outer>("[drive]\nstroke_m = 0.1\n").is_ok());
        let e = parse_toml::<Outer>("# a design\n[drive\n").unwrap_err();
        assert_eq!(e.field(), "text");
        let text = e.to_string();
        assert!(text.starts_with("text: line 2, column ") && !text.contains('\n'), "{text}");
        let e = parse_toml::<Outer>("[drive]\nstroke_m = 0.1\nbogus = 2\n").unwrap_err();
        assert_eq!(e.to_string(), "drive.bogus: line 3, column 1: unknown field `bogus`, expected `stroke_m`");
    }
}
