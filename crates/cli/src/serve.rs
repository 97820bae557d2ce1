//! `loomkin serve`: the workbench — a local web page with live plots and draggable points.

use crate::output::{self, outln};
use crate::util;
use anyhow::{Result, anyhow};
use clap::Args;

/// `loomkin serve`.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// Port to listen on; the server listens on 127.0.0.1 only (0 picks a free port).
    #[arg(long, default_value_t = loomkin_web::DEFAULT_PORT)]
    port: u16,
    /// Open the page in the default browser once the server listens.
    #[arg(long)]
    open: bool,
}

/// Runs `loomkin serve` until Ctrl-C.
pub fn run(a: ServeArgs) -> Result<()> {
    loomkin_web::serve_blocking(a.port, |url| {
        // The server runs on: a closed standard output is no reason to stop it.
        let _ = outln!("loomkin workbench: {url}  (listening on 127.0.0.1 only; Ctrl-C stops it)");
        if a.open
            && let Err(msg) = loomkin_web::open_browser(url, output::warning)
        {
            output::warning(msg);
        }
    })
    .map_err(|e| util::failure(anyhow!("cannot serve on 127.0.0.1:{}: {e}", a.port)))
}
