//! The page: HTML, CSS and JavaScript written for loomkin, embedded in the binary.

use axum::http::header;
use axum::response::{IntoResponse, Response};

/// The page skeleton.
pub const INDEX_HTML: &str = include_str!("../assets/index.html");
/// The style sheet.
pub const STYLE_CSS: &str = include_str!("../assets/style.css");
/// The chart drawing code (canvas: axes, grid, legend, hover read-out, draggable points).
pub const CHARTS_JS: &str = include_str!("../assets/charts.js");
/// The views and their wiring to the JSON API.
pub const APP_JS: &str = include_str!("../assets/app.js");
/// The cam view.
pub const CAM_JS: &str = include_str!("../assets/cam.js");
/// The loom view.
pub const LOOM_JS: &str = include_str!("../assets/loom.js");
/// The drive view.
pub const DRIVE_JS: &str = include_str!("../assets/drive.js");
/// The servo shedding view.
pub const ESHED_JS: &str = include_str!("../assets/eshed.js");
/// The insertion view.
pub const INSERTION_JS: &str = include_str!("../assets/insertion.js");

fn asset(body: &'static str, content_type: &'static str) -> Response {
    ([(header::CONTENT_TYPE, content_type), (header::CACHE_CONTROL, "no-cache")], body).into_response()
}

pub(crate) async fn index() -> Response {
    asset(INDEX_HTML, "text/html; charset=utf-8")
}

pub(crate) async fn style() -> Response {
    asset(STYLE_CSS, "text/css; charset=utf-8")
}

pub(crate) async fn charts() -> Response {
    asset(CHARTS_JS, "text/javascript; charset=utf-8")
}

pub(crate) async fn app() -> Response {
    asset(APP_JS, "text/javascript; charset=utf-8")
}

pub(crate) async fn cam() -> Response {
    asset(CAM_JS, "text/javascript; charset=utf-8")
}

pub(crate) async fn loom() -> Response {
    asset(LOOM_JS, "text/javascript; charset=utf-8")
}

pub(crate) async fn drive() -> Response {
    asset(DRIVE_JS, "text/javascript; charset=utf-8")
}

pub(crate) async fn insertion() -> Response {
    asset(INSERTION_JS, "text/javascript; charset=utf-8")
}

pub(crate) async fn eshed() -> Response {
    asset(ESHED_JS, "text/javascript; charset=utf-8")
}
