//! Errors of the workbench: every failure becomes a JSON answer naming the field.

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use loomkin_units::{FieldError, RangeError};
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
    /// A value outside its allowed range (422); its field is the JSON path of the request.
    #[error(transparent)]
    Range(RangeError),
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
    /// The client did not send its request body in time (408; the connection is closed).
    #[error("body: the {what} did not arrive within {} s", loomkin_units::compact(limit.as_secs_f64()))]
    Timeout {
        /// What did not arrive (`request body`).
        what: &'static str,
        /// The time allowed.
        limit: std::time::Duration,
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
    /// A library's refusal, placed at the request field the error names itself
    /// ([`FieldError::field`]), or at `default_field` when it names none.
    pub fn from_library<E: FieldError>(e: &E, default_field: &str) -> Self {
        Self::invalid(e.field().unwrap_or(default_field), e)
    }

    /// Shorthand for [`ApiError::Invalid`]; the message is prefixed with the field unless it
    /// already names it (library messages write numbers with [`loomkin_units::compact`]).
    pub fn invalid(field: impl Into<String>, message: impl std::fmt::Display) -> Self {
        let (field, message) = (field.into(), message.to_string());
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
            ApiError::Range(e) => {
                let field = join(&e.field);
                ApiError::Range(e.renamed(field))
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
            ApiError::Range(_) | ApiError::Invalid { .. } => StatusCode::UNPROCESSABLE_ENTITY,
            ApiError::TooLarge { .. } => StatusCode::PAYLOAD_TOO_LARGE,
            ApiError::Timeout { .. } => StatusCode::REQUEST_TIMEOUT,
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
            ApiError::Range(e) => &e.field,
            ApiError::BadJson { field, .. }
            | ApiError::Invalid { field, .. }
            | ApiError::NotFound { field, .. }
            | ApiError::MethodNotAllowed { field, .. }
            | ApiError::Forbidden { field, .. } => field,
            ApiError::TooLarge { .. } | ApiError::Timeout { .. } | ApiError::Busy { .. } => "body",
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
        // A library's message may quote a huge value sent in the request: keep it one short line.
        let body = ErrorBody { error: crate::json::cut(&self.to_string()), field: self.field() };
        let mut res = (self.status(), Json(body)).into_response();
        match self {
            ApiError::Busy { retry_after_s } => {
                res.headers_mut().insert(axum::http::header::RETRY_AFTER, axum::http::HeaderValue::from(retry_after_s));
            }
            // The rest of a late body may still come: end the connection rather than read it as a request.
            ApiError::Timeout { .. } | ApiError::TooLarge { .. } => {
                res.headers_mut().insert(axum::http::header::CONNECTION, axum::http::HeaderValue::from_static("close"));
            }
            _ => {}
        }
        res
    }
}

impl From<RangeError> for ApiError {
    fn from(e: RangeError) -> Self {
        ApiError::Range(e)
    }
}

/// Checks a count `min ≤ n ≤ max`.
pub fn check_count(field: &str, n: usize, min: usize, max: usize) -> Result<usize, ApiError> {
    Ok(loomkin_units::check_count(field, n, min, max)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_units::ShaftSpeed;

    #[test]
    fn statuses_are_client_errors_and_name_the_field() {
        let e = check_count("samples", 1_000_000_000, 2, 5000).unwrap_err();
        assert_eq!(e.status(), StatusCode::UNPROCESSABLE_ENTITY);
        assert_eq!(e.field(), "samples");
        assert!(e.to_string().starts_with("samples = 1e9 is out of range"), "{e}");
        assert_eq!(ApiError::TooLarge { limit: 10 }.status(), StatusCode::PAYLOAD_TOO_LARGE);
        assert_eq!(check_count("n", 3, 2, 4), Ok(3));
    }

    #[test]
    fn range_errors_are_data_and_numbers_short() {
        let e: ApiError = loomkin_servo::Drive::STROKE_M.check(1e300).unwrap_err().into();
        assert_eq!(e.to_string(), "drive.stroke_m = 1e300 is out of range: allowed 1e-9 ≤ drive.stroke_m ≤ 100 m");
        // The field of a library error comes from the error, not from its text.
        let lib = loomkin_laws::LawError::from(loomkin_laws::RAMP.check("ramp", 1.0).unwrap_err());
        assert_eq!(ApiError::from_library(&lib, "law").field(), "ramp");
    }

    #[test]
    fn within_prefixes_the_field_and_the_message() {
        let e = ApiError::invalid("drive.stroke_m", "drive.stroke_m = -1 is out of range").within("design");
        assert_eq!(e.field(), "design.drive.stroke_m");
        assert_eq!(e.to_string(), "design.drive.stroke_m = -1 is out of range");
        let e = ApiError::invalid("points[3]", "X must increase").within("design");
        assert_eq!((e.field(), e.to_string().as_str()), ("design.points[3]", "design.points[3]: X must increase"));
        let e = ApiError::from(ShaftSpeed::RANGE.check("speeds_rpm[0]", 0.0).unwrap_err()).within("design");
        assert_eq!(e.field(), "design.speeds_rpm[0]");
        assert_eq!(
            e.to_string(),
            "design.speeds_rpm[0] = 0 is out of range: allowed 0.001 ≤ design.speeds_rpm[0] ≤ 100000 rpm"
        );
    }
}
