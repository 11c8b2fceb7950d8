//! `--view`: the live view of a run in a browser (sitlog-view, feature
//! `view`). [`LiveView::start`] serves the task's diagram and waits for the
//! page; the run's transitions go to its observer; [`LiveView::finish`]
//! tells the page how the run ended and stops the server. Without the
//! feature, `--view` is refused (exit status 2).

use crate::assets::Assets;
use crate::cli::RunArgs;
use sitlog_runtime::machine::Observer;
use std::io::Write;

/// The live view of one run, its page open.
pub(crate) struct LiveView {
    #[cfg(feature = "view")]
    view: sitlog_view::View,
    /// Without the feature no live view exists.
    #[cfg(not(feature = "view"))]
    never: std::convert::Infallible,
}

#[cfg(feature = "view")]
impl LiveView {
    /// Serves the diagram of `assets` on `args.view_port` and waits for the
    /// page; `Err` holds the exit status and the message of a failure.
    pub(crate) fn start(
        args: &RunArgs,
        assets: &Assets,
        stderr: &mut dyn Write,
    ) -> Result<LiveView, (u8, String)> {
        let diagram = match assets
            .diagram
            .as_deref()
            .map(sitlog_graph::Diagram::from_json)
        {
            Some(Ok(d)) => d,
            Some(Err(e)) => return Err((2, format!("error: the task's diagram: {e}"))),
            None => {
                return Err((
                    2,
                    "error: --view needs the program's diagram, and this task has none".to_owned(),
                ))
            }
        };
        let view = match sitlog_view::View::start(diagram, args.view_port) {
            Ok(v) => v,
            Err(e) => {
                return Err((
                    2,
                    format!(
                        "error: cannot serve the live view on 127.0.0.1:{}: {e}",
                        args.view_port
                    ),
                ))
            }
        };
        let _ = writeln!(
            stderr,
            "live view at {} (the task starts when the page is open)",
            view.url()
        );
        let _ = stderr.flush();
        view.wait_for_viewer(None);
        Ok(LiveView { view })
    }

    /// The page's observer of the run, waiting `delay_ms` after each
    /// transition.
    pub(crate) fn observer(&self, delay_ms: u64) -> Box<dyn Observer + Send> {
        Box::new(
            self.view
                .observer(std::time::Duration::from_millis(delay_ms)),
        )
    }

    /// Shows how the run ended (its exit status `code`) and stops the server.
    pub(crate) fn finish(self, code: u8) {
        let status = match code {
            0 => "ok",
            1 => "error",
            _ => "stopped",
        };
        self.view
            .finish(status, "", std::time::Duration::from_secs(3));
    }
}

#[cfg(not(feature = "view"))]
impl LiveView {
    /// Without the feature: refused, exit status 2.
    pub(crate) fn start(
        _: &RunArgs,
        _: &Assets,
        _: &mut dyn Write,
    ) -> Result<LiveView, (u8, String)> {
        Err((
            2,
            "error: --view: this build has no live view (feature `view` of sitlog-robot)"
                .to_owned(),
        ))
    }

    pub(crate) fn observer(&self, _: u64) -> Box<dyn Observer + Send> {
        match self.never {}
    }

    pub(crate) fn finish(self, _: u8) {
        match self.never {}
    }
}
