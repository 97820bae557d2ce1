//! Errors of the workbench: every failure becomes a JSON answer naming the field.

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use thiserror::Error;

/// Why a request was refused or failed.
///
/// Every variant answers the browser with a JSON body `{"error": "...", "field": "..."}` and a
/// 4xx status (5xx only for [`ApiError::Internal`], which a correct server never sends).
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ApiError {
    /// The body is not JSON, or JSON of the wrong shape (400).
    #[error("{field}: {message}")]
    BadJson {
        /// JSON path of the offending value (`drive.stroke_m`), or `body`.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// A value outside its allowed range (422).
    #[error(
        "{field} = {} is out of range: allowed {} ≤ {field} ≤ {}{unit}",
        compact_number(*value),
        compact_number(*min),
        compact_number(*max)
    )]
    OutOfRange {
        /// JSON path of the offending value.
        field: String,
        /// Value given.
        value: f64,
        /// Lowest allowed value.
        min: f64,
        /// Highest allowed value.
        max: f64,
        /// Unit suffix with a leading space, or empty.
        unit: String,
    },
    /// A value the domain libraries refused (422); `message` is their explanation (and names
    /// the field).
    #[error("{message}")]
    Invalid {
        /// JSON path or library field name of the offending value.
        field: String,
        /// The library's explanation.
        message: String,
    },
    /// The request body is larger than [`crate::MAX_BODY_BYTES`] (413).
    #[error("body: the request body is larger than {limit} bytes")]
    TooLarge {
        /// The limit in bytes.
        limit: usize,
    },
    /// No such endpoint or view (404).
    #[error("{field}: {message}")]
    NotFound {
        /// What was asked for (`path`).
        field: String,
        /// Explanation.
        message: String,
    },
    /// The endpoint exists but not for this method (405).
    #[error("{field}: {message}")]
    MethodNotAllowed {
        /// `method`.
        field: String,
        /// Which method was used and which are allowed.
        message: String,
    },
    /// A request from a host name other than the loopback names (403).
    #[error("{field}: {message}")]
    Forbidden {
        /// `host`.
        field: String,
        /// Explanation.
        message: String,
    },
    /// Every slot for heavy computations is taken (503, with a `Retry-After` header).
    #[error("body: the server is busy with other heavy computations; try again in {retry_after_s} s")]
    Busy {
        /// Seconds to wait before trying again.
        retry_after_s: u64,
    },
    /// The computation failed unexpectedly (500); the server keeps serving.
    #[error("internal error: {0}")]
    Internal(String),
}

impl ApiError {
    /// Shorthand for [`ApiError::OutOfRange`].
    pub fn out_of_range(field: impl Into<String>, value: f64, min: f64, max: f64, unit: &str) -> Self {
        let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
        Self::OutOfRange { field: field.into(), value, min, max, unit }
    }

    /// Shorthand for [`ApiError::Invalid`]; the message is prefixed with the field unless it
    /// already names it, and very long numbers in it (`1e300` written out in 301 digits by a
    /// library's message) are shortened to exponent form.
    pub fn invalid(field: impl Into<String>, message: impl std::fmt::Display) -> Self {
        let (field, message) = (field.into(), compact_numbers(&message.to_string()));
        let message = if message.contains(&field) { message } else { format!("{field}: {message}") };
        Self::Invalid { field, message }
    }

    /// The same error with its field placed under `prefix` in the request (`drive.stroke_m` →
    /// `design.drive.stroke_m`), so that `field` is always the JSON path of the request.
    pub fn within(self, prefix: &str) -> Self {
        let join =
            |field: &str| if field.starts_with('[') { format!("{prefix}{field}") } else { format!("{prefix}.{field}") };
        match self {
            ApiError::BadJson { field, message } => ApiError::BadJson { field: join(&field), message },
            ApiError::OutOfRange { field, value, min, max, unit } => {
                ApiError::OutOfRange { field: join(&field), value, min, max, unit }
            }
            ApiError::Invalid { field, message } => {
                let full = join(&field);
                let message = match message.strip_prefix(field.as_str()) {
                    Some(rest) => format!("{full}{rest}"),
                    None => format!("{full}: {message}"),
                };
                ApiError::Invalid { field: full, message }
            }
            e => e,
        }
    }

    /// The HTTP status of the answer.
    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::BadJson { .. } => StatusCode::BAD_REQUEST,
            ApiError::OutOfRange { .. } | ApiError::Invalid { .. } => StatusCode::UNPROCESSABLE_ENTITY,
            ApiError::TooLarge { .. } => StatusCode::PAYLOAD_TOO_LARGE,
            ApiError::NotFound { .. } => StatusCode::NOT_FOUND,
            ApiError::MethodNotAllowed { .. } => StatusCode::METHOD_NOT_ALLOWED,
            ApiError::Forbidden { .. } => StatusCode::FORBIDDEN,
            ApiError::Busy { .. } => StatusCode::SERVICE_UNAVAILABLE,
            ApiError::Internal(_) => StatusCode::INTERNAL_SERVER_ERROR,
        }
    }

    /// The name of the offending field (`body` when the whole request is at fault).
    pub fn field(&self) -> &str {
        match self {
            ApiError::BadJson { field, .. }
            | ApiError::OutOfRange { field, .. }
            | ApiError::Invalid { field, .. }
            | ApiError::NotFound { field, .. }
            | ApiError::MethodNotAllowed { field, .. }
            | ApiError::Forbidden { field, .. } => field,
            ApiError::TooLarge { .. } | ApiError::Busy { .. } => "body",
            ApiError::Internal(_) => "",
        }
    }
}

#[derive(Serialize)]
struct ErrorBody<'a> {
    error: String,
    field: &'a str,
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = ErrorBody { error: self.to_string(), field: self.field() };
        let mut res = (self.status(), Json(body)).into_response();
        if let ApiError::Busy { retry_after_s } = self {
            res.headers_mut().insert(axum::http::header::RETRY_AFTER, axum::http::HeaderValue::from(retry_after_s));
        }
        res
    }
}

/// A number for a message: shortest round-trip form, in exponent form below 1e-4 and from 1e16
/// on in magnitude (`1e-9`, `1e300`: never 300 digits).
pub fn compact_number(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-4 || v.abs() >= 1e16) { format!("{v:e}") } else { v.to_string() }
}

/// Rewrites every run of digits longer than 24 characters (a huge or tiny `f64` written out in
/// full) in exponent form; the rest of the text is kept.
fn compact_numbers(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        if !b[i].is_ascii_digit() {
            let ch = text[i..].chars().next().map_or(1, char::len_utf8);
            out.push_str(&text[i..i + ch]);
            i += ch;
            continue;
        }
        let start = i;
        while i < b.len() && (b[i].is_ascii_digit() || (b[i] == b'.' && i + 1 < b.len() && b[i + 1].is_ascii_digit())) {
            i += 1;
        }
        let run = &text[start..i];
        match run.parse::<f64>() {
            Ok(v) if run.len() > 24 => out.push_str(&format!("{v:e}")),
            _ => out.push_str(run),
        }
    }
    out
}

/// Checks `min ≤ value ≤ max` and finiteness of a request value.
pub fn check_range(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64, ApiError> {
    if !value.is_finite() {
        return Err(ApiError::BadJson { field: field.into(), message: "must be a finite number".into() });
    }
    if value < min || value > max {
        return Err(ApiError::out_of_range(field, value, min, max, unit));
    }
    Ok(value)
}

/// Checks a count `min ≤ n ≤ max`.
pub fn check_count(field: &str, n: usize, min: usize, max: usize) -> Result<usize, ApiError> {
    if n < min || n > max {
        return Err(ApiError::out_of_range(field, n as f64, min as f64, max as f64, ""));
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statuses_are_client_errors_and_name_the_field() {
        let e = ApiError::out_of_range("samples", 1e9, 2.0, 5000.0, "");
        assert_eq!(e.status(), StatusCode::UNPROCESSABLE_ENTITY);
        assert_eq!(e.field(), "samples");
        assert!(e.to_string().contains("samples = 1000000000"));
        assert_eq!(ApiError::TooLarge { limit: 10 }.status(), StatusCode::PAYLOAD_TOO_LARGE);
        assert!(check_range("x", f64::NAN, 0.0, 1.0, "").is_err());
        assert!(check_range("x", 2.0, 0.0, 1.0, "m").unwrap_err().to_string().contains("≤ 1 m"));
        assert_eq!(check_count("n", 3, 2, 4), Ok(3));
    }

    #[test]
    fn huge_and_tiny_numbers_are_written_short() {
        let e = check_range("drive.stroke_m", 1e300, 1e-9, 100.0, "m").unwrap_err().to_string();
        assert_eq!(e, "drive.stroke_m = 1e300 is out of range: allowed 1e-9 ≤ drive.stroke_m ≤ 100 m");
        // A library message with the value written out in full.
        let long = format!("x = {} is out of range: allowed 0 ≤ x ≤ 2.5", 1e300);
        assert!(long.len() > 300);
        let e = ApiError::invalid("x", &long);
        assert_eq!(e.to_string(), "x = 1e300 is out of range: allowed 0 ≤ x ≤ 2.5");
        let tiny = format!("point [{}, 1]", 1e-300);
        assert_eq!(ApiError::invalid("x0", tiny).to_string(), "x0: point [1e-300, 1]");
        // Ordinary numbers, units and non-ASCII text are kept.
        let e = ApiError::invalid("φ2", "at φ2 = 91.000°: 0.500099999999999 ≥ 12 m/s²");
        assert_eq!(e.to_string(), "at φ2 = 91.000°: 0.500099999999999 ≥ 12 m/s²");
    }

    #[test]
    fn within_prefixes_the_field_and_the_message() {
        let e = ApiError::invalid("drive.stroke_m", "drive.stroke_m = -1 is out of range").within("design");
        assert_eq!(e.field(), "design.drive.stroke_m");
        assert_eq!(e.to_string(), "design.drive.stroke_m = -1 is out of range");
        let e = ApiError::invalid("points[3]", "X must increase").within("design");
        assert_eq!((e.field(), e.to_string().as_str()), ("design.points[3]", "design.points[3]: X must increase"));
        let e = check_range("speeds_rpm[0]", 0.0, 1.0, 2.0, "").unwrap_err().within("design");
        assert_eq!(e.field(), "design.speeds_rpm[0]");
    }
}
