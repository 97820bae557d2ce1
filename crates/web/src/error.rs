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
    #[error("{field} = {value} is out of range: allowed {min} ≤ {field} ≤ {max}{unit}")]
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
    /// already names it.
    pub fn invalid(field: impl Into<String>, message: impl std::fmt::Display) -> Self {
        let (field, message) = (field.into(), message.to_string());
        let message = if message.contains(&field) { message } else { format!("{field}: {message}") };
        Self::Invalid { field, message }
    }

    /// The HTTP status of the answer.
    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::BadJson { .. } => StatusCode::BAD_REQUEST,
            ApiError::OutOfRange { .. } | ApiError::Invalid { .. } => StatusCode::UNPROCESSABLE_ENTITY,
            ApiError::TooLarge { .. } => StatusCode::PAYLOAD_TOO_LARGE,
            ApiError::NotFound { .. } => StatusCode::NOT_FOUND,
            ApiError::Internal(_) => StatusCode::INTERNAL_SERVER_ERROR,
        }
    }

    /// The name of the offending field (`body` when the whole request is at fault).
    pub fn field(&self) -> &str {
        match self {
            ApiError::BadJson { field, .. }
            | ApiError::OutOfRange { field, .. }
            | ApiError::Invalid { field, .. }
            | ApiError::NotFound { field, .. } => field,
            ApiError::TooLarge { .. } => "body",
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
        (self.status(), Json(body)).into_response()
    }
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
}
