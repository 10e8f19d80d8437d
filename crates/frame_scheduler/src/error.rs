//! Errors: building a graph, accessing a resource inside a pass, running a frame.

use crate::report::FrameReport;

/// What a pass body returns: any error, boxed (the pass's own error type converts with `?`).
pub type PassResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// A graph that cannot be scheduled. Every variant names the passes and resources involved.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GraphError {
    #[error("dependency cycle between passes: {}", cycle_text(.passes))]
    Cycle { passes: Vec<String> },
    #[error("resource '{resource}' is read by {} but no pass writes it and it is not an input", quoted(.readers))]
    MissingProducer { resource: String, readers: Vec<String> },
    #[error("resource '{resource}' is written by more than one pass: {}", quoted(.writers))]
    DoubleWriter { resource: String, writers: Vec<String> },
    #[error(
        "{reader_lane} pass '{reader}' reads '{resource}' written by {writer_lane} pass '{writer}': \
         CPU and GPU exchange data only through a sync pass"
    )]
    NeedsSync {
        reader: String,
        reader_lane: crate::Lane,
        resource: String,
        writer: String,
        writer_lane: crate::Lane,
    },
    #[error("pass '{pass}' writes '{resource}', which is an external input of the graph")]
    WritesInput { pass: String, resource: String },
    #[error("pass '{pass}' uses a resource handle of another graph")]
    ForeignHandle { pass: String },
    #[error("two passes are named '{name}'; pass names must be unique")]
    DuplicatePass { name: String },
    #[error("amortised pass '{pass}': {problem}")]
    BadAmortisation { pass: String, problem: String },
}

fn quoted(names: &[String]) -> String {
    names.iter().map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", ")
}

fn cycle_text(passes: &[String]) -> String {
    let mut s = quoted(passes).replace(", ", " -> ");
    if let Some(first) = passes.first() {
        s.push_str(&format!(" -> '{first}'"));
    }
    s
}

/// A resource access inside a pass body that cannot be honoured.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ResourceError {
    #[error("pass '{pass}' did not declare that it {access} '{resource}'")]
    Undeclared { pass: String, resource: String, access: &'static str },
    #[error("resource '{resource}' has no value yet (its producer never stored one)")]
    Empty { resource: String },
    #[error("resource '{resource}' is not produced this frame: {why}")]
    Inactive { resource: String, why: String },
    #[error("a resource handle of another graph was used in pass '{pass}'")]
    ForeignHandle { pass: String },
}

/// A frame that did not complete.
#[derive(Debug, thiserror::Error)]
pub enum FrameError {
    /// A pass body returned an error; passes after it were skipped. The report of the partial
    /// frame is attached.
    #[error("pass '{pass}' failed")]
    PassFailed {
        pass: String,
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
        report: Box<FrameReport>,
    },
}
