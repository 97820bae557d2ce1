//! Serves the workbench without the CLI: `cargo run -p loomkin-web --example serve [PORT]`.

#[tokio::main]
async fn main() -> std::io::Result<()> {
    let port = std::env::args().nth(1).and_then(|p| p.parse().ok()).unwrap_or(0);
    let bound = loomkin_web::bind(port).await?;
    println!("loomkin workbench at {} (127.0.0.1 only)", bound.url());
    bound.run().await
}
