//! The tuning server: HTTP on a loopback address, every request checked by the [`Guard`], the
//! page and its JSON and image endpoints answered with one [`Session`].
//!
//! | request | body | answer |
//! | --- | --- | --- |
//! | `GET /?token=T` | | the page |
//! | `GET /api/state?frame=F` | | [`StateView`](super::StateView) as JSON |
//! | `POST /api/frame?format=png\|raw` | [`FrameRequest`] | the frame's pixels |
//! | `POST /api/pick` | `{frame, x, y}` | [`Pick`](super::Pick) |
//! | `POST /api/drag?format=…` | [`DragRequest`] | the frame with the layer placed; the changes in `X-Glint-Changes` |
//! | `POST /api/shade_drag?format=…` | [`ShadeDragRequest`] | the frame with the shadow's edge placed; the changes in `X-Glint-Changes` |
//! | `POST /api/draw` | [`DrawRequest`] | `{version, changes}` once the drawn outline is written |
//! | `POST /api/commit` | `{changes: [Change]}` | `{version}` once written |
//! | `POST /api/undo`, `/api/redo` | | `{version}` |
//! | `GET /api/wait?version=V` | | `{version}` when it is no longer V, or after 20 s |
//!
//! Pixels travel as PNG (the default: compressed for speed, decoded by the browser off its main
//! thread, about 10% sooner on the screen than raw for a 640×360 teapot, docs/tune.md) or raw
//! (`format=raw`: RGBA8 rows from the top); the size is in `X-Glint-Width` and
//! `X-Glint-Height`. Errors are `{"error": "one line"}` with
//! status 400 (bad input), 401 (token), 403 (host or origin), 409 (file changed elsewhere) or
//! 500.

use std::net::{IpAddr, SocketAddr};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use axum::body::{Body, Bytes};
use axum::extract::{Query, Request, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use tokio::sync::{oneshot, watch};

use super::change::Change;
use super::error::TuneError;
use super::guard::{new_token, Guard, Refusal};
use super::session::{
    DragRequest, DrawRequest, FrameImage, FrameRequest, Session, ShadeDragRequest,
};

/// Where the server listens and which names it answers to.
#[derive(Clone, Debug)]
pub struct ServerOptions {
    /// The address to listen on: loopback unless the user asks for another.
    pub bind: IpAddr,
    /// The port; 0 lets the system choose a free one.
    pub port: u16,
    /// More host names requests may name the server by (its name on the network, when bound
    /// to another address than loopback).
    pub hosts: Vec<String>,
}

impl Default for ServerOptions {
    fn default() -> Self {
        Self {
            bind: IpAddr::from([127, 0, 0, 1]),
            port: 0,
            hosts: Vec::new(),
        }
    }
}

/// What every request shares.
struct Shared {
    session: Mutex<Session>,
    guard: Guard,
    versions: watch::Sender<u64>,
}

impl Shared {
    fn session(&self) -> MutexGuard<'_, Session> {
        // A request never panics while holding the lock; should one, its state is still the
        // file's last good text.
        self.session
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    fn publish(&self, version: u64) {
        self.versions.send_replace(version);
    }
}

/// A running tuning server.
pub struct TuneServer {
    address: SocketAddr,
    token: String,
    shared: Arc<Shared>,
    runtime: Option<tokio::runtime::Runtime>,
    stop: Option<oneshot::Sender<()>>,
    served: Option<tokio::task::JoinHandle<()>>,
}

impl TuneServer {
    /// Starts serving `session` as `options` say, on threads of its own; returns once it
    /// listens.
    pub fn start(session: Session, options: &ServerOptions) -> std::io::Result<Self> {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .thread_name("glint-tune")
            .enable_io()
            .enable_time()
            .build()?;
        let listener = std::net::TcpListener::bind((options.bind, options.port))?;
        listener.set_nonblocking(true)?;
        let address = listener.local_addr()?;
        let token = new_token().map_err(|e| std::io::Error::other(e.to_string()))?;
        let mut names = vec!["localhost".to_string()];
        names.push(match options.bind {
            IpAddr::V4(ip) => ip.to_string(),
            IpAddr::V6(ip) => format!("[{ip}]"),
        });
        if options.bind.is_loopback() {
            names.extend(["127.0.0.1".to_string(), "[::1]".to_string()]);
        }
        names.extend(options.hosts.iter().cloned());
        let version = session.version();
        let (versions, _) = watch::channel(version);
        let shared = Arc::new(Shared {
            session: Mutex::new(session),
            guard: Guard::new(token.clone(), &names, address.port()),
            versions,
        });
        let app = router(Arc::clone(&shared));
        let (stop, stopped) = oneshot::channel::<()>();
        let served = runtime.block_on(async {
            let listener = tokio::net::TcpListener::from_std(listener)?;
            Ok::<_, std::io::Error>(tokio::spawn(async move {
                let _ = axum::serve(listener, app)
                    .with_graceful_shutdown(async {
                        let _ = stopped.await;
                    })
                    .await;
            }))
        })?;
        Ok(Self {
            address,
            token,
            shared,
            runtime: Some(runtime),
            stop: Some(stop),
            served: Some(served),
        })
    }

    /// The address it listens on.
    #[must_use]
    pub fn address(&self) -> SocketAddr {
        self.address
    }

    /// The session's token, which every request must carry.
    #[must_use]
    pub fn token(&self) -> &str {
        &self.token
    }

    /// The page's address, token included: what the user opens.
    #[must_use]
    pub fn url(&self) -> String {
        let host = if self.address.ip().is_loopback() && self.address.is_ipv4() {
            "127.0.0.1".to_string()
        } else {
            match self.address.ip() {
                IpAddr::V4(ip) => ip.to_string(),
                IpAddr::V6(ip) => format!("[{ip}]"),
            }
        };
        format!(
            "http://{host}:{}/?token={}",
            self.address.port(),
            self.token
        )
    }

    /// Takes in a change of the shot's files made elsewhere ([`Session::inputs_changed`]); the
    /// page learns of it through `/api/wait`.
    pub fn inputs_changed(&self) {
        let mut session = self.shared.session();
        if session.inputs_changed() {
            let version = session.version();
            drop(session);
            self.shared.publish(version);
        }
    }

    /// Stops listening, lets the requests under way finish, and returns.
    pub fn stop(mut self) {
        self.shut_down();
    }

    fn shut_down(&mut self) {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        if let (Some(runtime), Some(served)) = (self.runtime.take(), self.served.take()) {
            let _ = runtime.block_on(served);
            runtime.shutdown_timeout(Duration::from_secs(5));
        }
    }
}

impl Drop for TuneServer {
    fn drop(&mut self) {
        self.shut_down();
    }
}

fn router(shared: Arc<Shared>) -> Router {
    Router::new()
        .route("/", get(page))
        .route("/api/state", get(state))
        .route("/api/frame", post(frame))
        .route("/api/pick", post(pick))
        .route("/api/drag", post(drag))
        .route("/api/shade_drag", post(shade_drag))
        .route("/api/draw", post(draw))
        .route("/api/commit", post(commit))
        .route("/api/undo", post(undo))
        .route("/api/redo", post(redo))
        .route("/api/wait", get(wait))
        .fallback(not_found)
        .layer(middleware::from_fn_with_state(Arc::clone(&shared), guard))
        .with_state(shared)
}

/// The one-line JSON error answer.
fn error_response(status: u16, message: &str) -> Response {
    #[derive(Serialize)]
    struct Error<'a> {
        error: &'a str,
    }
    let status = StatusCode::from_u16(status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
    (status, axum::Json(Error { error: message })).into_response()
}

impl IntoResponse for TuneError {
    fn into_response(self) -> Response {
        error_response(self.status(), &self.to_string())
    }
}

/// The token a request carries: its `X-Glint-Token` header, or its `token` query parameter.
fn token_of(request: &Request) -> Option<String> {
    if let Some(value) = request.headers().get("x-glint-token") {
        return value.to_str().ok().map(str::to_string);
    }
    let query = request.uri().query()?;
    query
        .split('&')
        .find_map(|pair| pair.strip_prefix("token="))
        .map(str::to_string)
}

async fn guard(State(shared): State<Arc<Shared>>, request: Request, next: Next) -> Response {
    let checked = {
        let header = |name: header::HeaderName| {
            request
                .headers()
                .get(name)
                .map(|v| v.to_str().unwrap_or("(not text)").to_string())
        };
        let (host, origin) = (header(header::HOST), header(header::ORIGIN));
        let token = token_of(&request);
        shared
            .guard
            .check(host.as_deref(), origin.as_deref(), token.as_deref())
    };
    match checked {
        Ok(()) => {
            let mut response = next.run(request).await;
            let headers = response.headers_mut();
            headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
            headers.insert(
                header::X_CONTENT_TYPE_OPTIONS,
                HeaderValue::from_static("nosniff"),
            );
            response
        }
        Err(refusal @ (Refusal::Token | Refusal::Host(_) | Refusal::Origin(_))) => {
            error_response(refusal.status(), &refusal.message())
        }
    }
}

async fn not_found() -> Response {
    error_response(404, "no such page; the page is at / and the API under /api")
}

const PAGE: &str = include_str!("page/index.html");
const SCRIPT: &str = include_str!("page/tune.js");
const STYLE: &str = include_str!("page/tune.css");

async fn page() -> Response {
    let html = PAGE
        .replace("/*STYLE*/", STYLE)
        .replace("/*SCRIPT*/", SCRIPT);
    let mut response = (StatusCode::OK, html).into_response();
    let headers = response.headers_mut();
    headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("text/html; charset=utf-8"),
    );
    headers.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(
            "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; \
             img-src data: blob:; connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; \
             form-action 'none'",
        ),
    );
    response
}

/// Runs `work` with the session on the blocking pool.
async fn with_session<T: Send + 'static>(
    shared: &Arc<Shared>,
    work: impl FnOnce(&mut Session) -> Result<T, TuneError> + Send + 'static,
) -> Result<T, TuneError> {
    let shared = Arc::clone(shared);
    tokio::task::spawn_blocking(move || work(&mut shared.session()))
        .await
        .map_err(|e| TuneError::Failed(format!("the request failed: {e}")))?
}

/// `body` read as JSON of `T`; a malformed body is a bad request that says where.
fn json_body<T: DeserializeOwned>(body: &Bytes) -> Result<T, TuneError> {
    serde_json::from_slice(body).map_err(|e| TuneError::Bad(format!("the request body: {e}")))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FrameQuery {
    frame: Option<f64>,
    #[allow(dead_code)]
    token: Option<String>,
}

async fn state(
    State(shared): State<Arc<Shared>>,
    query: Result<Query<FrameQuery>, axum::extract::rejection::QueryRejection>,
) -> Response {
    let query = match query {
        Ok(Query(q)) => q,
        Err(e) => return TuneError::Bad(e.body_text()).into_response(),
    };
    let result = with_session(&shared, move |session| {
        let frame = match query.frame {
            Some(frame) => frame,
            None => session.state(0.0).map(|s| s.frames[0] as f64)?,
        };
        session.state(frame)
    })
    .await;
    match result {
        Ok(view) => axum::Json(view).into_response(),
        Err(e) => e.into_response(),
    }
}

/// How pixels travel.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
enum Format {
    Raw,
    #[default]
    Png,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FormatQuery {
    #[serde(default)]
    format: Format,
    #[allow(dead_code)]
    token: Option<String>,
}

fn format_of(
    query: Result<Query<FormatQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Format, TuneError> {
    query
        .map(|Query(q)| q.format)
        .map_err(|e| TuneError::Bad(e.body_text()))
}

/// A frame's pixels as `format` carries them, with its size and timing in headers; a frame
/// that cannot be encoded is a failure ([`TuneError::Failed`]).
fn image_response(
    image: &FrameImage,
    format: Format,
    extra: Option<(&'static str, String)>,
    started: Instant,
) -> Result<Response, TuneError> {
    let encoding = Instant::now();
    let (content_type, body) = match format {
        Format::Raw => ("application/octet-stream", image.rgba.clone()),
        Format::Png => ("image/png", png_bytes(image)?),
    };
    let encode_ms = encoding.elapsed().as_secs_f64() * 1e3;
    let mut response = Response::new(Body::from(body));
    let headers: &mut HeaderMap = response.headers_mut();
    let mut set = |name: &'static str, value: String| {
        if let Ok(value) = HeaderValue::from_str(&value) {
            headers.insert(name, value);
        }
    };
    set("content-type", content_type.to_string());
    set("x-glint-width", image.width.to_string());
    set("x-glint-height", image.height.to_string());
    set("x-glint-render-ms", format!("{:.2}", image.render_ms));
    // The encoding alone, and all the server did from the request's body to the response's
    // (reading and checking the changed shot, rendering, the overlays, encoding).
    set("x-glint-encode-ms", format!("{encode_ms:.2}"));
    set(
        "x-glint-server-ms",
        format!("{:.2}", started.elapsed().as_secs_f64() * 1e3),
    );
    set("x-glint-stages", image.stages.join(","));
    if let Some(centres) = &image.centres {
        // `x,y,shown` per centre, `;` between them: the pixel and whether the frame shows it.
        let listed: Vec<String> = centres
            .iter()
            .map(|([x, y], shown)| format!("{x:.2},{y:.2},{}", u8::from(*shown)))
            .collect();
        set("x-glint-centres", listed.join(";"));
    }
    if let Some((name, value)) = extra {
        set(name, value);
    }
    Ok(response)
}

/// The frame as a PNG, compressed for speed rather than size; a frame whose pixels are not
/// `width × height × 4` bytes, or that the encoder refuses (an empty one), is a failure.
fn png_bytes(image: &FrameImage) -> Result<Vec<u8>, TuneError> {
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    use image::ImageEncoder;
    let (width, height) = (image.width, image.height);
    let expected = u64::from(width) * u64::from(height) * 4;
    if image.rgba.len() as u64 != expected {
        return Err(TuneError::Failed(format!(
            "encoding the frame as PNG: a {width}×{height} frame has {expected} bytes of \
             pixels, not {}",
            image.rgba.len()
        )));
    }
    let mut out = Vec::new();
    let encoder = PngEncoder::new_with_quality(&mut out, CompressionType::Fast, FilterType::Sub);
    encoder
        .write_image(&image.rgba, width, height, image::ExtendedColorType::Rgba8)
        .map_err(|e| {
            TuneError::Failed(format!("encoding the {width}×{height} frame as PNG: {e}"))
        })?;
    Ok(out)
}

async fn frame(
    State(shared): State<Arc<Shared>>,
    query: Result<Query<FormatQuery>, axum::extract::rejection::QueryRejection>,
    body: Bytes,
) -> Response {
    let started = Instant::now();
    let result = async {
        let format = format_of(query)?;
        let request: FrameRequest = json_body(&body)?;
        let image = with_session(&shared, move |s| s.render(&request)).await?;
        image_response(&image, format, None, started)
    }
    .await;
    result.unwrap_or_else(IntoResponse::into_response)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PickRequest {
    frame: f64,
    x: f64,
    y: f64,
}

async fn pick(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    let result = async {
        let request: PickRequest = json_body(&body)?;
        with_session(&shared, move |s| {
            s.pick(request.frame, (request.x, request.y))
        })
        .await
    }
    .await;
    match result {
        Ok(pick) => axum::Json(pick).into_response(),
        Err(e) => e.into_response(),
    }
}

async fn drag(
    State(shared): State<Arc<Shared>>,
    query: Result<Query<FormatQuery>, axum::extract::rejection::QueryRejection>,
    body: Bytes,
) -> Response {
    dragged(&shared, query, &body, |s, request: DragRequest| {
        let changes = s.drag_changes(&request)?;
        Ok(FrameRequest {
            frame: request.frame,
            quality: request.quality,
            overlays: request.overlays,
            changes,
        })
    })
    .await
}

async fn shade_drag(
    State(shared): State<Arc<Shared>>,
    query: Result<Query<FormatQuery>, axum::extract::rejection::QueryRejection>,
    body: Bytes,
) -> Response {
    dragged(&shared, query, &body, |s, request: ShadeDragRequest| {
        let changes = s.shade_drag_changes(&request)?;
        Ok(FrameRequest {
            frame: request.frame,
            quality: request.quality,
            overlays: request.overlays,
            changes,
        })
    })
    .await
}

/// A drag's answer: the body read as a request `R`, the frame `placed` makes of it (with the
/// changes the drag makes) rendered, and those changes in `X-Glint-Changes`.
async fn dragged<R: DeserializeOwned + Send + 'static>(
    shared: &Arc<Shared>,
    query: Result<Query<FormatQuery>, axum::extract::rejection::QueryRejection>,
    body: &Bytes,
    placed: impl FnOnce(&mut Session, R) -> Result<FrameRequest, TuneError> + Send + 'static,
) -> Response {
    let started = Instant::now();
    let result = async {
        let format = format_of(query)?;
        let request: R = json_body(body)?;
        let (image, changes) = with_session(shared, move |s| {
            let frame = placed(s, request)?;
            Ok((s.render(&frame)?, frame.changes))
        })
        .await?;
        let changes =
            serde_json::to_string(&changes).map_err(|e| TuneError::Failed(e.to_string()))?;
        image_response(&image, format, Some(("x-glint-changes", changes)), started)
    }
    .await;
    result.unwrap_or_else(IntoResponse::into_response)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CommitRequest {
    changes: Vec<Change>,
}

#[derive(Serialize)]
struct Version {
    version: u64,
}

/// Answers a change to the file: the new version, published to every page waiting.
async fn changed(
    shared: &Arc<Shared>,
    work: impl FnOnce(&mut Session) -> Result<u64, TuneError> + Send + 'static,
) -> Response {
    match with_session(shared, work).await {
        Ok(version) => {
            shared.publish(version);
            axum::Json(Version { version }).into_response()
        }
        Err(e) => {
            // A conflict took in the file as it is now: tell the pages.
            let version = shared.session().version();
            shared.publish(version);
            e.into_response()
        }
    }
}

async fn commit(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    let request: CommitRequest = match json_body(&body) {
        Ok(request) => request,
        Err(e) => return e.into_response(),
    };
    changed(&shared, move |s| s.commit(&request.changes)).await
}

#[derive(Serialize)]
struct Drawn {
    version: u64,
    changes: Vec<Change>,
}

/// Maps a drawn outline's pixels to the layer's t′ and writes it: the new version, published
/// to every page waiting, and the change written. Nothing is written when a point cannot be
/// mapped or the outline is not one a layer can have.
async fn draw(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    let request: DrawRequest = match json_body(&body) {
        Ok(request) => request,
        Err(e) => return e.into_response(),
    };
    let result = with_session(&shared, move |s| {
        let changes = s.draw_changes(&request)?;
        let version = s.commit(&changes)?;
        Ok(Drawn { version, changes })
    })
    .await;
    match result {
        Ok(drawn) => {
            shared.publish(drawn.version);
            axum::Json(drawn).into_response()
        }
        Err(e) => {
            let version = shared.session().version();
            shared.publish(version);
            e.into_response()
        }
    }
}

async fn undo(State(shared): State<Arc<Shared>>) -> Response {
    changed(&shared, Session::undo).await
}

async fn redo(State(shared): State<Arc<Shared>>) -> Response {
    changed(&shared, Session::redo).await
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WaitQuery {
    version: u64,
    #[allow(dead_code)]
    token: Option<String>,
}

/// How long `/api/wait` holds a request when nothing changes.
const WAIT: Duration = Duration::from_secs(20);

async fn wait(
    State(shared): State<Arc<Shared>>,
    query: Result<Query<WaitQuery>, axum::extract::rejection::QueryRejection>,
) -> Response {
    let seen = match query {
        Ok(Query(q)) => q.version,
        Err(e) => return TuneError::Bad(e.body_text()).into_response(),
    };
    let mut versions = shared.versions.subscribe();
    let _ = tokio::time::timeout(WAIT, versions.wait_for(|&v| v != seen)).await;
    let version = *versions.borrow();
    axum::Json(Version { version }).into_response()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame of `width × height` pixels holding `bytes` bytes.
    fn image_of(width: u32, height: u32, bytes: usize) -> FrameImage {
        FrameImage {
            width,
            height,
            rgba: vec![128; bytes],
            render_ms: 1.0,
            stages: vec!["shade"],
            centres: None,
        }
    }

    /// The status and the body of the answer to `image` asked for as a PNG.
    fn png_answer(image: &FrameImage) -> (StatusCode, Vec<u8>) {
        let response = image_response(image, Format::Png, None, Instant::now())
            .unwrap_or_else(IntoResponse::into_response);
        let status = response.status();
        let runtime = tokio::runtime::Builder::new_current_thread()
            .build()
            .unwrap();
        let body = runtime
            .block_on(axum::body::to_bytes(response.into_body(), usize::MAX))
            .unwrap();
        (status, body.to_vec())
    }

    #[test]
    fn a_frame_encodes_as_a_png() {
        let (status, body) = png_answer(&image_of(3, 2, 3 * 2 * 4));
        assert_eq!(status, StatusCode::OK);
        assert_eq!(&body[1..4], b"PNG");
    }

    #[test]
    fn a_frame_the_encoder_fails_on_is_a_500_with_one_line_saying_why() {
        for (image, says) in [
            (
                image_of(3, 2, 5),
                "a 3×2 frame has 24 bytes of pixels, not 5",
            ),
            (image_of(0, 0, 0), "encoding the 0×0 frame as PNG: "),
        ] {
            let (status, body) = png_answer(&image);
            let body = String::from_utf8(body).unwrap();
            assert_eq!(status, StatusCode::INTERNAL_SERVER_ERROR);
            assert_eq!(body.lines().count(), 1, "{body}");
            let error: serde_json::Value = serde_json::from_str(&body).unwrap();
            let message = error["error"].as_str().unwrap();
            assert!(message.contains(says), "{message}");
        }
    }
}
