//! What one load shares across every file it reads: the root folder references may not leave,
//! the chain of files being loaded (include cycles and depth), and the budgets that keep a
//! small hostile file from exhausting memory or time; and the warnings gathered on the way.

use crate::{LoadError, LoadErrorKind, LoadWarning, LoadWarningKind};
use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// Limits a load enforces. [`Default`] is what [`crate::load`], [`crate::load_gltf`],
/// [`crate::load_obj`] and [`crate::load_scene_file`] use; [`crate::load_with`] takes others.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadOptions {
    /// Relative references (glTF URIs, `mtllib` and texture paths, scene-file meshes) resolve
    /// against the referencing file's folder and must stay inside the folder of the first file
    /// loaded (the root); absolute references and `..` that leave the root are rejected.
    /// `false` opts out (device files and folders are refused either way).
    pub confine_to_root: bool,
    /// Longest chain of scene files referencing scene files (the first file counts as 1).
    pub max_include_depth: usize,
    /// Mesh instances in the whole load (glTF node x primitive, OBJ object).
    pub max_instances: usize,
    /// Triangles in the whole load, summed over instances.
    pub max_triangles: u64,
    /// Decoded texels of one image (each costs 4 bytes as RGBA8 and 16 + 16/3 as linear `f32`
    /// RGBA with its mips).
    pub max_image_pixels: u64,
    /// Decoded texels over every image of the load.
    pub max_total_pixels: u64,
    /// Largest file read, bytes.
    pub max_file_bytes: u64,
    /// Refuse what a load otherwise works around with a warning ([`crate::LoadWarning`]: a
    /// missing texture or material library, a feature that is not supported): the first one
    /// is the load's error ([`LoadErrorKind::Strict`]). `false` (the default) loads the scene
    /// with stand-ins and lists the warnings in `Scene::warnings`.
    pub strict: bool,
}

impl Default for LoadOptions {
    fn default() -> Self {
        Self {
            confine_to_root: true,
            max_include_depth: 8,
            max_instances: 1 << 16,
            max_triangles: 1 << 24,
            max_image_pixels: 1 << 25,
            max_total_pixels: 1 << 27,
            max_file_bytes: 1 << 30,
            strict: false,
        }
    }
}

/// The state of one load.
pub(crate) struct Ctx {
    pub opts: LoadOptions,
    /// Absolute, `..`-free root folder; `None` for in-memory loads without a base folder.
    root: Option<PathBuf>,
    /// Files being loaded, outermost first (absolute, normalised).
    chain: Vec<PathBuf>,
    instances: usize,
    triangles: u64,
    pixels: u64,
    /// Each warning once, in the order met.
    warnings: Vec<LoadWarning>,
}

impl Ctx {
    pub fn new(opts: &LoadOptions, root: Option<&Path>) -> Self {
        Self {
            opts: opts.clone(),
            root: root.map(absolute),
            chain: Vec::new(),
            instances: 0,
            triangles: 0,
            pixels: 0,
            warnings: Vec::new(),
        }
    }

    /// A context rooted at the folder of `file`.
    pub fn for_file(opts: &LoadOptions, file: &Path) -> Self {
        Self::new(opts, Some(file.parent().unwrap_or(Path::new(""))))
    }

    /// Records a warning (once: a repeat of one already recorded is dropped), or with
    /// [`LoadOptions::strict`] returns it as the load's error.
    pub fn warn(
        &mut self,
        file: &str,
        element: impl Into<String>,
        kind: LoadWarningKind,
    ) -> Result<(), LoadError> {
        if self.opts.strict {
            return Err(LoadError::new(file, element, LoadErrorKind::Strict(Box::new(kind))));
        }
        let w = LoadWarning::new(file, element, kind);
        if !self.warnings.contains(&w) {
            self.warnings.push(w);
        }
        Ok(())
    }

    /// The warnings recorded so far, in the order met.
    pub fn take_warnings(&mut self) -> Vec<LoadWarning> {
        std::mem::take(&mut self.warnings)
    }

    /// `reference` (as written in a file in folder `base`) as a path, if it may be read.
    /// Backslashes are separators (files written on Windows: `.\wood.jpg`, `tex\wood.jpg`), and
    /// a drive letter (`C:`) makes a path absolute, as it does there.
    pub fn resolve(&self, base: &Path, reference: &str) -> Result<PathBuf, LoadErrorKind> {
        let slashed = reference.replace('\\', "/");
        let rel = Path::new(&slashed);
        let joined = base.join(rel);
        let Some(root) = self.root.as_ref().filter(|_| self.opts.confine_to_root) else {
            return Ok(joined);
        };
        let escapes = |why: &str| LoadErrorKind::PathEscapes(format!("`{reference}` {why}"));
        let drive = slashed.as_bytes();
        let drive = drive.len() >= 2 && drive[0].is_ascii_alphabetic() && drive[1] == b':';
        if rel.has_root() || rel.is_absolute() || drive {
            return Err(escapes("is absolute"));
        }
        if !absolute(&joined).starts_with(root) {
            return Err(escapes(&format!("leaves the root folder {}", root.display())));
        }
        // A symbolic link inside the root may still point out of it.
        if let (Ok(real), Ok(real_root)) = (joined.canonicalize(), root.canonicalize())
            && !real.starts_with(&real_root)
        {
            return Err(escapes(&format!("leads out of the root folder {}", root.display())));
        }
        Ok(joined)
    }

    /// Reads a regular file of at most `max_file_bytes` (never a device, FIFO or folder).
    pub fn read(&self, path: &Path) -> Result<Vec<u8>, LoadErrorKind> {
        let io = |e: std::io::Error| LoadErrorKind::Io {
            path: path.display().to_string(),
            cause: crate::Cause::new(e),
        };
        let meta = std::fs::metadata(path).map_err(io)?;
        if !meta.is_file() {
            return Err(LoadErrorKind::NotAFile(path.display().to_string()));
        }
        let max = self.opts.max_file_bytes;
        let too_big = || LoadErrorKind::Budget { what: "file bytes", limit: max };
        if meta.len() > max {
            return Err(too_big());
        }
        let mut out = Vec::with_capacity(meta.len() as usize);
        std::fs::File::open(path).map_err(io)?.take(max + 1).read_to_end(&mut out).map_err(io)?;
        if out.len() as u64 > max {
            return Err(too_big());
        }
        Ok(out)
    }

    /// Enters `path` (a scene file or mesh it references): refuses a file already being
    /// loaded and chains longer than `max_include_depth`. Pair with [`Ctx::leave`].
    pub fn enter(&mut self, path: &Path) -> Result<(), LoadErrorKind> {
        let key = path.canonicalize().unwrap_or_else(|_| absolute(path));
        if let Some(i) = self.chain.iter().position(|p| *p == key) {
            let names: Vec<String> =
                self.chain[i..].iter().chain([&key]).map(|p| p.display().to_string()).collect();
            return Err(LoadErrorKind::IncludeCycle(names.join(" -> ")));
        }
        if self.chain.len() >= self.opts.max_include_depth {
            return Err(LoadErrorKind::Budget {
                what: "include depth",
                limit: self.opts.max_include_depth as u64,
            });
        }
        self.chain.push(key);
        Ok(())
    }

    pub fn leave(&mut self) {
        self.chain.pop();
    }

    /// Counts one mesh instance of `triangles` triangles against the budgets.
    pub fn add_instance(&mut self, triangles: u64) -> Result<(), LoadErrorKind> {
        self.instances += 1;
        self.triangles = self.triangles.saturating_add(triangles);
        if self.instances > self.opts.max_instances {
            return Err(LoadErrorKind::Budget {
                what: "mesh instances",
                limit: self.opts.max_instances as u64,
            });
        }
        if self.triangles > self.opts.max_triangles {
            return Err(LoadErrorKind::Budget {
                what: "triangles",
                limit: self.opts.max_triangles,
            });
        }
        Ok(())
    }

    /// Counts an image of `width` x `height` texels against the budgets, before decoding it.
    pub fn add_image(&mut self, width: u32, height: u32) -> Result<(), LoadErrorKind> {
        let n = width as u64 * height as u64;
        if n > self.opts.max_image_pixels {
            return Err(LoadErrorKind::Budget {
                what: "decoded pixels of one image",
                limit: self.opts.max_image_pixels,
            });
        }
        self.pixels += n;
        if self.pixels > self.opts.max_total_pixels {
            return Err(LoadErrorKind::Budget {
                what: "decoded pixels of all images",
                limit: self.opts.max_total_pixels,
            });
        }
        Ok(())
    }
}

/// `p` made absolute (against the working folder) with `.` and `..` resolved lexically.
fn absolute(p: &Path) -> PathBuf {
    let p = std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}
