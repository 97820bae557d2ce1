//! The router, the loopback listener and the guard rails around every request.

use crate::limits::{DEFAULT_SAMPLES, MAX_BODY_BYTES, MAX_SAMPLES, MAX_SPEEDS, MIN_SAMPLES};
use crate::{ApiError, ApiJson, assets, catalogue};
use axum::Router;
use axum::extract::{DefaultBodyLimit, OriginalUri, Request};
use axum::http::{Method, StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use serde::Serialize;
use std::net::{Ipv4Addr, SocketAddr};
use tokio::net::TcpListener;

/// The whole application: page, assets and JSON API.
///
/// Bodies are limited to [`MAX_BODY_BYTES`]; requests whose `Host` is not a loopback name (DNS
/// rebinding) or whose `Origin` is not the workbench's own page are refused with 403, and wrong
/// methods (405) and unknown paths (404) answer the same JSON `{"error", "field"}` as every
/// other refusal.
pub fn router() -> Router {
    let api = Router::new()
        .route("/info", get(info))
        .route("/laws", get(catalogue::get_catalogue))
        .route("/laws/compare", post(catalogue::post_compare))
        .merge(crate::servo_api::routes())
        .merge(crate::picking_api::routes())
        .merge(crate::shed_api::routes())
        .merge(crate::dobby_api::routes())
        .merge(crate::dynamics_api::routes())
        .merge(crate::cam_api::routes())
        .merge(crate::loom_api::routes())
        .merge(crate::drive_api::routes())
        .merge(crate::insertion_api::routes())
        .merge(crate::eshed_api::routes())
        .merge(crate::schema::routes())
        .fallback(api_not_found);
    Router::new()
        .route("/", get(assets::index))
        .route("/style.css", get(assets::style))
        .route("/charts.js", get(assets::charts))
        .route("/app.js", get(assets::app))
        .route("/cam.js", get(assets::cam))
        .route("/loom.js", get(assets::loom))
        .route("/drive.js", get(assets::drive))
        .route("/insertion.js", get(assets::insertion))
        .route("/eshed.js", get(assets::eshed))
        .route("/favicon.ico", get(|| async { StatusCode::NO_CONTENT }))
        .nest("/api", api)
        .layer(DefaultBodyLimit::max(MAX_BODY_BYTES))
        .layer(middleware::from_fn(guard))
}

async fn api_not_found(method: Method, OriginalUri(uri): OriginalUri) -> ApiError {
    ApiError::NotFound { field: "path".into(), message: format!("no endpoint {method} {}", uri.path()) }
}

/// Whether `authority` (a `Host` header, or an origin without its `http://`) is a loopback name
/// with an optional port, read as RFC 3986 reads an authority: `host [":" port]`, the host an IP
/// literal in brackets (`[::1]`) or a name (`127.0.0.1`, `localhost`, any case), the port digits
/// only. The host must be one of the loopback names exactly: `localhost:80@evil.com`,
/// `127.0.0.1.evil.com`, `localhost.` and a user part are refused (DNS-rebinding forms).
fn is_loopback_authority(authority: &str) -> bool {
    let (host, port) = match authority.strip_prefix('[') {
        Some(rest) => match rest.split_once(']') {
            Some((literal, after)) => (&authority[..literal.len() + 2], after),
            None => return false,
        },
        None => authority.find(':').map_or((authority, ""), |i| authority.split_at(i)),
    };
    let port_ok = match port.strip_prefix(':') {
        None => port.is_empty(),
        Some(digits) => {
            digits.len() <= 5
                && digits.bytes().all(|b| b.is_ascii_digit())
                && digits.parse::<u32>().map_or(digits.is_empty(), |p| p <= 65_535)
        }
    };
    port_ok && (host == "127.0.0.1" || host.eq_ignore_ascii_case("localhost") || host == "[::1]")
}

/// Loopback host check, JSON bodies for the router's own refusals, security headers.
async fn guard(req: Request, next: Next) -> Response {
    if let Some(host) = req.headers().get(header::HOST) {
        let host = host.to_str().unwrap_or("");
        if !is_loopback_authority(host) {
            let message = format!("the workbench answers only on 127.0.0.1, not on host '{host}'");
            return ApiError::Forbidden { field: "host".into(), message }.into_response();
        }
    }
    // A page elsewhere may still send a request here (a form or a text/plain POST needs no
    // preflight); browsers name its origin, so refuse any origin but the loopback names.
    if let Some(origin) = req.headers().get(header::ORIGIN) {
        let origin = origin.to_str().unwrap_or("");
        if !origin.strip_prefix("http://").is_some_and(is_loopback_authority) {
            let message = format!("the workbench answers only its own page, not a page from '{origin}'");
            return ApiError::Forbidden { field: "origin".into(), message }.into_response();
        }
    }
    let (method, path) = (req.method().clone(), req.uri().path().to_string());
    let mut res = next.run(req).await;
    // The router answers a wrong method (405) and an unknown page (404) with an empty body: say
    // what was wrong in the same JSON form as every other refusal.
    if res.headers().get(header::CONTENT_TYPE).is_none() {
        let refusal = match res.status() {
            StatusCode::METHOD_NOT_ALLOWED => {
                // Every route takes exactly one of GET and POST (the router adds the `Allow`
                // header after this layer has run).
                let hint = match method {
                    Method::GET | Method::HEAD => "this endpoint takes a POST with a JSON body",
                    Method::POST => "this endpoint answers GET",
                    _ => "the endpoints take GET or POST (see the Allow header)",
                };
                Some(ApiError::MethodNotAllowed {
                    field: "method".into(),
                    message: format!("{method} is not allowed on {path}: {hint}"),
                })
            }
            StatusCode::NOT_FOUND => {
                Some(ApiError::NotFound { field: "path".into(), message: format!("no page {method} {path}") })
            }
            _ => None,
        };
        if let Some(e) = refusal {
            res = e.into_response();
        }
    }
    let h = res.headers_mut();
    h.insert(
        header::CONTENT_SECURITY_POLICY,
        header::HeaderValue::from_static("default-src 'self'; img-src 'self' data: blob:; style-src 'self'"),
    );
    h.insert(header::X_CONTENT_TYPE_OPTIONS, header::HeaderValue::from_static("nosniff"));
    res
}

/// Runs a short computation in the light pool ([`crate::pool`]).
pub(crate) async fn blocking<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    crate::pool::light(f).await
}

/// `GET /api/info`: version, the views this build offers and the request limits.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Info {
    /// `loomkin`.
    pub name: &'static str,
    /// Crate version.
    pub version: &'static str,
    /// The views this build serves (`servo`, `catalogue`, …).
    pub views: Vec<&'static str>,
    /// Request limits.
    pub limits: Limits,
}

/// The request limits, as reported by `GET /api/info`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Limits {
    /// Largest request body, bytes.
    pub max_body_bytes: usize,
    /// Fewest samples per curve.
    pub min_samples: usize,
    /// Most samples per curve.
    pub max_samples: usize,
    /// Default samples per curve.
    pub default_samples: usize,
    /// Most speeds per request.
    pub max_speeds: usize,
    /// Time budget of one heavy computation, seconds ([`crate::HEAVY_BUDGET`]): the page's
    /// progress line counts against it.
    pub heavy_budget_s: f64,
}

/// The answer of `GET /api/info`.
pub fn info_value() -> Info {
    Info {
        name: "loomkin",
        version: env!("CARGO_PKG_VERSION"),
        views: crate::VIEWS.to_vec(),
        limits: Limits {
            max_body_bytes: MAX_BODY_BYTES,
            min_samples: MIN_SAMPLES,
            max_samples: MAX_SAMPLES,
            default_samples: DEFAULT_SAMPLES,
            max_speeds: MAX_SPEEDS,
            heavy_budget_s: crate::HEAVY_BUDGET.as_secs_f64(),
        },
    }
}

async fn info() -> ApiJson<Info> {
    ApiJson(info_value())
}

/// Longest time a client may take to send a request head (request line and headers).
pub const HEADER_READ_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(10);

/// Longest time a client may take to send a request body once its head has arrived (at most
/// [`MAX_BODY_BYTES`]); a body shorter than its `Content-Length` is answered 408 and the connection
/// closed.
pub const BODY_READ_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(10);

/// Connections served at once; further clients wait in the listener's queue until one ends. With
/// the body limit this bounds the memory of half-sent requests: at most this many bodies of at most
/// [`MAX_BODY_BYTES`] (64 MiB), each held at most [`BODY_READ_TIMEOUT`].
pub const MAX_CONNECTIONS: usize = 256;

/// A listener bound to 127.0.0.1, not yet serving.
#[derive(Debug)]
pub struct Bound {
    listener: TcpListener,
    addr: SocketAddr,
    header_timeout: std::time::Duration,
    body_timeout: std::time::Duration,
}

/// Binds 127.0.0.1:`port` (0 picks a free port). Never binds another interface.
pub async fn bind(port: u16) -> std::io::Result<Bound> {
    let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, port)).await?;
    let addr = listener.local_addr()?;
    Ok(Bound { listener, addr, header_timeout: HEADER_READ_TIMEOUT, body_timeout: BODY_READ_TIMEOUT })
}

impl Bound {
    /// The bound address (always 127.0.0.1).
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The same listener with another header read timeout (default [`HEADER_READ_TIMEOUT`]).
    pub fn with_header_timeout(mut self, timeout: std::time::Duration) -> Self {
        self.header_timeout = timeout;
        self
    }

    /// The same listener with another body read timeout (default [`BODY_READ_TIMEOUT`]).
    pub fn with_body_timeout(mut self, timeout: std::time::Duration) -> Self {
        self.body_timeout = timeout;
        self
    }

    /// The page's URL, `http://127.0.0.1:PORT/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Serves until `shutdown` completes. Each connection is HTTP/1.1 with a header read timeout
    /// (default [`HEADER_READ_TIMEOUT`]): a client that does not finish sending its request head in that
    /// time is disconnected, so half-sent requests are not held open; a body gets
    /// [`BODY_READ_TIMEOUT`] (then 408), and at most [`MAX_CONNECTIONS`] are served at once. A
    /// request hyper refuses before the router sees it (a malformed `Content-Length` or header) is
    /// answered with the same JSON `{"error", "field"}` as every other refusal.
    pub async fn run_until(self, shutdown: impl Future<Output = ()> + Send + 'static) -> std::io::Result<()> {
        let app = router().layer(axum::Extension(crate::json::BodyTimeout(self.body_timeout)));
        let header_timeout = self.header_timeout;
        let connections = std::sync::Arc::new(tokio::sync::Semaphore::new(MAX_CONNECTIONS));
        let mut shutdown = std::pin::pin!(shutdown);
        loop {
            let permit = tokio::select! {
                permit = connections.clone().acquire_owned() => match permit {
                    Ok(p) => p,
                    Err(_) => return Ok(()),
                },
                () = &mut shutdown => return Ok(()),
            };
            let (stream, _) = tokio::select! {
                accepted = self.listener.accept() => match accepted {
                    Ok(pair) => pair,
                    // A failed accept (out of file descriptors, a reset) ends that connection only.
                    Err(_) => {
                        tokio::time::sleep(std::time::Duration::from_millis(10)).await;
                        continue;
                    }
                },
                () = &mut shutdown => return Ok(()),
            };
            let service = hyper_util::service::TowerToHyperService::new(app.clone());
            tokio::spawn(async move {
                let _permit = permit;
                let _ = hyper::server::conn::http1::Builder::new()
                    .timer(hyper_util::rt::TokioTimer::new())
                    .header_read_timeout(header_timeout)
                    .serve_connection(hyper_util::rt::TokioIo::new(JsonRefusals::new(stream)), service)
                    .await;
            });
        }
    }

    /// Serves until Ctrl-C.
    pub async fn run(self) -> std::io::Result<()> {
        self.run_until(async {
            let _ = tokio::signal::ctrl_c().await;
        })
        .await
    }
}

/// A connection whose protocol-level refusals are JSON: hyper answers a request it cannot parse
/// (a `Content-Length` that is not a number or overflows, a malformed header, a head too large)
/// itself, before the router runs, with a bodiless `4xx`/`5xx` and `connection: close`. The
/// router never answers an error without a body, so such a head, written alone, is hyper's; it is
/// replaced by the same status with a JSON body naming what was wrong.
struct JsonRefusals<S> {
    inner: S,
    /// A replacement answer still to be written (its bytes and how many are written).
    pending: Option<(Vec<u8>, usize)>,
}

impl<S> JsonRefusals<S> {
    fn new(inner: S) -> Self {
        Self { inner, pending: None }
    }

    /// The JSON answer replacing `head` when it is one of hyper's bodiless refusals.
    fn replacement(head: &[u8]) -> Option<Vec<u8>> {
        let text = std::str::from_utf8(head).ok()?;
        let status: u16 = text.strip_prefix("HTTP/1.1 ")?.get(..3)?.parse().ok()?;
        let bodiless = text.ends_with("\r\n\r\n") && text.to_ascii_lowercase().contains("\r\ncontent-length: 0\r\n");
        if !(400..600).contains(&status) || !bodiless {
            return None;
        }
        let code = StatusCode::from_u16(status).ok()?;
        let message = match status {
            431 => "the request head is too large".to_string(),
            400 => "the request is not valid HTTP/1.1: a malformed request line or header (Content-Length must be \
                    a whole number of bytes)"
                .to_string(),
            _ => format!("the request was refused by the HTTP layer ({code})"),
        };
        let body = serde_json::json!({"error": format!("head: {message}"), "field": "head"}).to_string();
        Some(
            format!(
                "HTTP/1.1 {code}\r\ncontent-type: application/json\r\ncontent-length: {}\r\nconnection: close\r\n\r\n{body}",
                body.len()
            )
            .into_bytes(),
        )
    }

    /// Writes what is left of a replacement answer.
    fn poll_pending(&mut self, cx: &mut std::task::Context<'_>) -> std::task::Poll<std::io::Result<()>>
    where
        S: tokio::io::AsyncWrite + Unpin,
    {
        use std::task::Poll;
        while let Some((bytes, done)) = &mut self.pending {
            if *done == bytes.len() {
                self.pending = None;
                break;
            }
            match std::pin::Pin::new(&mut self.inner).poll_write(cx, &bytes[*done..]) {
                Poll::Ready(Ok(0)) => return Poll::Ready(Err(std::io::ErrorKind::WriteZero.into())),
                Poll::Ready(Ok(n)) => *done += n,
                Poll::Ready(Err(e)) => return Poll::Ready(Err(e)),
                Poll::Pending => return Poll::Pending,
            }
        }
        Poll::Ready(Ok(()))
    }
}

impl<S: tokio::io::AsyncRead + Unpin> tokio::io::AsyncRead for JsonRefusals<S> {
    fn poll_read(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
        buf: &mut tokio::io::ReadBuf<'_>,
    ) -> std::task::Poll<std::io::Result<()>> {
        std::pin::Pin::new(&mut self.inner).poll_read(cx, buf)
    }
}

impl<S: tokio::io::AsyncWrite + Unpin> tokio::io::AsyncWrite for JsonRefusals<S> {
    fn poll_write(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
        buf: &[u8],
    ) -> std::task::Poll<std::io::Result<usize>> {
        std::task::ready!(self.poll_pending(cx))?;
        if let Some(answer) = Self::replacement(buf) {
            self.pending = Some((answer, 0));
            return std::task::Poll::Ready(Ok(buf.len()));
        }
        std::pin::Pin::new(&mut self.inner).poll_write(cx, buf)
    }

    fn poll_write_vectored(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
        bufs: &[std::io::IoSlice<'_>],
    ) -> std::task::Poll<std::io::Result<usize>> {
        std::task::ready!(self.poll_pending(cx))?;
        let mut parts = bufs.iter().filter(|b| !b.is_empty());
        if let (Some(only), None) = (parts.next(), parts.next())
            && let Some(answer) = Self::replacement(only)
        {
            self.pending = Some((answer, 0));
            return std::task::Poll::Ready(Ok(only.len()));
        }
        std::pin::Pin::new(&mut self.inner).poll_write_vectored(cx, bufs)
    }

    fn is_write_vectored(&self) -> bool {
        self.inner.is_write_vectored()
    }

    fn poll_flush(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
    ) -> std::task::Poll<std::io::Result<()>> {
        std::task::ready!(self.poll_pending(cx))?;
        std::pin::Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
    ) -> std::task::Poll<std::io::Result<()>> {
        std::task::ready!(self.poll_pending(cx))?;
        std::pin::Pin::new(&mut self.inner).poll_shutdown(cx)
    }
}

/// The port `loomkin serve` listens on when none is given (0 picks a free one).
pub const DEFAULT_PORT: u16 = 8765;

/// Binds 127.0.0.1:`port`, calls `on_ready` with the page's URL, and serves until Ctrl-C on a
/// runtime of its own (what `loomkin serve` runs; for callers without an async runtime).
pub fn serve_blocking(port: u16, on_ready: impl FnOnce(&str)) -> std::io::Result<()> {
    let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build()?;
    rt.block_on(async {
        let bound = bind(port).await?;
        on_ready(&bound.url());
        bound.run().await
    })
}

/// Asks the desktop to open `url` in the default browser (`xdg-open`, `open` or `start`).
///
/// On a Unix desktop other than macOS, nothing is started without a display (`DISPLAY` and
/// `WAYLAND_DISPLAY` unset or empty): `xdg-open` would fail there after the fact. Otherwise the
/// opener runs in the background and a thread waits for it, so it never lingers as a zombie; if
/// it exits with a failure, `on_failure` gets the one-line reason. Returns the reason at once when
/// no opener could be started. The server runs on either way.
pub fn open_browser(url: &str, on_failure: impl FnOnce(String) + Send + 'static) -> Result<(), String> {
    let unix_desktop = !cfg!(target_os = "macos") && !cfg!(windows);
    if unix_desktop && !has_display(|name| std::env::var_os(name)) {
        return Err(format!(
            "no display to open a browser on (DISPLAY and WAYLAND_DISPLAY are unset); open {url} yourself"
        ));
    }
    let (name, mut cmd) = if cfg!(target_os = "macos") {
        ("open", std::process::Command::new("open"))
    } else if cfg!(windows) {
        let mut c = std::process::Command::new("cmd");
        c.args(["/C", "start", ""]);
        ("start", c)
    } else {
        ("xdg-open", std::process::Command::new("xdg-open"))
    };
    let mut child = cmd
        .arg(url)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .map_err(|e| format!("could not start a browser ({name}: {e}); open {url} yourself"))?;
    let url = url.to_string();
    std::thread::spawn(move || match child.wait() {
        Ok(status) if status.success() => {}
        Ok(status) => on_failure(format!("{name} could not open a browser ({status}); open {url} yourself")),
        Err(e) => on_failure(format!("{name}: {e}; open {url} yourself")),
    });
    Ok(())
}

/// Whether a display is named by `DISPLAY` or `WAYLAND_DISPLAY` (non-empty), read through `var`.
fn has_display(var: impl Fn(&str) -> Option<std::ffi::OsString>) -> bool {
    ["DISPLAY", "WAYLAND_DISPLAY"].iter().any(|v| var(v).is_some_and(|s| !s.is_empty()))
}

#[cfg(test)]
mod tests {
    use super::{JsonRefusals, has_display, is_loopback_authority};

    #[test]
    fn only_hypers_bodiless_refusals_are_replaced() {
        let hyper_400 = b"HTTP/1.1 400 Bad Request\r\nconnection: close\r\ncontent-length: 0\r\ndate: x\r\n\r\n";
        let text = String::from_utf8(JsonRefusals::<()>::replacement(hyper_400).unwrap()).unwrap();
        let (head, body) = text.split_once("\r\n\r\n").unwrap();
        assert!(head.starts_with("HTTP/1.1 400 Bad Request\r\n") && head.contains("application/json"), "{head}");
        assert!(head.contains(&format!("content-length: {}", body.len())), "{head}");
        let v: serde_json::Value = serde_json::from_str(body).unwrap();
        assert_eq!(v["field"], "head");
        assert!(v["error"].as_str().unwrap().contains("Content-Length"), "{v}");
        let big = b"HTTP/1.1 431 Request Header Fields Too Large\r\ncontent-length: 0\r\n\r\n";
        assert!(String::from_utf8(JsonRefusals::<()>::replacement(big).unwrap()).unwrap().contains("too large"));
        // Answers of the router: a body follows (or is in the same write), or not an error.
        for kept in [
            &b"HTTP/1.1 400 Bad Request\r\ncontent-type: application/json\r\ncontent-length: 40\r\n\r\n"[..],
            b"HTTP/1.1 204 No Content\r\ncontent-length: 0\r\n\r\n",
            b"HTTP/1.1 400 Bad Request\r\ncontent-length: 0\r\n\r\n{}",
            b"{\"error\": \"HTTP/1.1 400\"}",
        ] {
            assert!(JsonRefusals::<()>::replacement(kept).is_none(), "{}", String::from_utf8_lossy(kept));
        }
    }

    #[test]
    fn only_the_loopback_names_pass_as_an_authority() {
        for ok in ["127.0.0.1", "127.0.0.1:8765", "localhost", "LocalHost:80", "[::1]", "[::1]:8765", "localhost:"] {
            assert!(is_loopback_authority(ok), "{ok} refused");
        }
        for bad in [
            "localhost:80@evil.com",
            "127.0.0.1@evil.com",
            "user@localhost",
            "localhost.evil.com",
            "127.0.0.1.evil.com:8765",
            "evil.com",
            "localhost.",
            "127.0.0.1:80:80",
            "localhost:8o",
            "localhost:65536",
            "localhost:123456",
            "[::1]evil",
            "[::1",
            "[::2]:8765",
            "[0:0:0:0:0:0:0:1]x",
            "",
            ":8765",
            "127.0.0.2",
            "localhost/evil",
        ] {
            assert!(!is_loopback_authority(bad), "{bad} accepted");
        }
    }
    use std::ffi::OsString;

    #[test]
    fn a_display_is_a_non_empty_display_variable() {
        let env = |pairs: &'static [(&'static str, &'static str)]| {
            move |name: &str| pairs.iter().find(|(k, _)| *k == name).map(|(_, v)| OsString::from(v))
        };
        assert!(!has_display(env(&[])));
        assert!(!has_display(env(&[("DISPLAY", ""), ("WAYLAND_DISPLAY", "")])));
        assert!(has_display(env(&[("DISPLAY", ":0")])));
        assert!(has_display(env(&[("WAYLAND_DISPLAY", "wayland-0")])));
    }
}
