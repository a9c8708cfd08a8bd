//! Scenes: the RON format ([`types`]), reading with located errors, validation, and scenes
//! generated from OBJ networks ([`obj_import`]).
pub mod locate;
pub mod obj_import;
pub mod translate;
pub mod types;
pub mod validate;

use std::fmt;
use std::path::{Path, PathBuf};

pub use types::Scene;

/// A semantic error in one field of a scene, before it is located in the text.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    pub section: &'static str,
    pub item: locate::Item,
    pub field: String,
    pub message: String,
}

impl FieldError {
    pub fn new(section: &'static str, index: usize, field: &str, message: String) -> Self {
        FieldError {
            section,
            item: locate::Item::Index(index),
            field: field.to_string(),
            message,
        }
    }
    pub fn keyed(section: &'static str, key: &str, field: &str, message: String) -> Self {
        FieldError {
            section,
            item: locate::Item::Key(key.to_string()),
            field: field.to_string(),
            message,
        }
    }
    pub fn global(section: &'static str, field: &str, message: String) -> Self {
        FieldError {
            section,
            item: locate::Item::None,
            field: field.to_string(),
            message,
        }
    }

    /// `section[index].field` or `section["key"].field`.
    pub fn path(&self) -> String {
        let item = match &self.item {
            locate::Item::Index(i) => format!("[{i}]"),
            locate::Item::Key(k) => format!("[\"{k}\"]"),
            locate::Item::None => String::new(),
        };
        if self.field.is_empty() {
            format!("{}{item}", self.section)
        } else {
            format!("{}{item}.{}", self.section, self.field)
        }
    }
}

/// An error reading a scene, located in its file.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    pub file: String,
    pub line: Option<usize>,
    pub column: Option<usize>,
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.line, self.column) {
            (Some(l), Some(c)) => write!(f, "{}:{l}:{c}: {}", self.file, self.message),
            _ => write!(f, "{}: {}", self.file, self.message),
        }
    }
}

impl std::error::Error for SceneError {}

impl SceneError {
    pub fn from_field(file: &str, src: &str, e: &FieldError) -> Self {
        let pos = locate::locate(src, e.section, &e.item, &e.field);
        SceneError {
            file: file.to_string(),
            line: pos.map(|p| p.0),
            column: pos.map(|p| p.1),
            message: format!("{}: {}", e.path(), e.message),
        }
    }
}

/// Parses and validates a scene from text; `file` names it in errors.
pub fn parse(file: &str, src: &str) -> Result<Scene, SceneError> {
    // Implicit `Some` lets scenes write `poisson_ratio: 0.5` as the contract does, while
    // `Some(..)` and `None` are still accepted. (UNWRAP_VARIANT_NEWTYPES would also unwrap
    // `Some((x, y, z))` and break the contract's `move_to` syntax, so `Elastic` is a struct
    // variant instead.)
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let scene: Scene = options.from_str(src).map_err(|e| {
        let (line, col) = (e.span.start.line, e.span.start.col);
        SceneError {
            file: file.to_string(),
            line: Some(line),
            column: Some(col),
            message: syntax_message(&e.code.to_string(), src, line, col),
        }
    })?;
    if let Some((key, line, col)) = locate::duplicate_key(src, "materials") {
        return Err(SceneError {
            file: file.to_string(),
            line: Some(line),
            column: Some(col),
            message: format!("materials: duplicate material name \"{key}\""),
        });
    }
    validate::validate(&scene).map_err(|e| SceneError::from_field(file, src, &e))?;
    let mut scene = scene;
    read_target_mesh(&mut scene, file, src)?;
    Ok(scene)
}

/// Largest target mesh file read, bytes.
pub const MAX_MESH_BYTES: u64 = 1 << 30;

/// Reads a `Mesh` target, its path relative to the scene file's folder. Errors in the mesh name
/// the mesh file and the line of the bad element; a missing file, the scene's `target.path`.
fn read_target_mesh(scene: &mut Scene, file: &str, src: &str) -> Result<(), SceneError> {
    let Some(types::Target::Mesh { path, surface }) = &mut scene.target else {
        return Ok(());
    };
    let base = Path::new(file).parent().unwrap_or(Path::new(""));
    let full = base.join(path.as_str());
    if let Err(why) = inside_scene_folder(base, path) {
        return Err(SceneError::from_field(
            file,
            src,
            &FieldError::global("target", "path", why),
        ));
    }
    match crate::surface::Surface::load(&full, MAX_MESH_BYTES) {
        Ok(s) => {
            surface.0 = Some(std::sync::Arc::new(s));
            // The path now names the mesh from anywhere: a copy of the scene that loses the
            // loaded mesh (serialized and read back, edited by a sweep) reads it again.
            *path = full.display().to_string();
            Ok(())
        }
        Err(e) if e.line.is_none() => Err(SceneError::from_field(
            file,
            src,
            &FieldError::global("target", "path", format!("{}: {}", e.file, e.message)),
        )),
        Err(e) => Err(SceneError {
            file: e.file,
            line: e.line,
            // A mesh's problems are whole records: their first column.
            column: e.line.map(|_| 1),
            message: format!("target mesh: {}", e.message),
        }),
    }
}

/// A scene names files relative to its folder, and a relative path stays inside it (after
/// symbolic links): a scene from elsewhere must not make rodnet read the user's other files.
/// An absolute path is the scene author's explicit choice and is read as given (errors about
/// its content name lines, never its text).
fn inside_scene_folder(base: &Path, given: &str) -> Result<(), String> {
    stays_inside(base, Path::new(given)).map_err(|folder| {
        format!(
            "\"{given}\" leads outside the scene file's folder ({}): a relative path must stay \
             inside it; give an absolute path to read a mesh elsewhere",
            folder.display()
        )
    })
}

/// Whether the relative path `given`, taken from `folder`, stays inside it: no `..` that climbs
/// out, and, for the part that exists, no symbolic link that leads out. An absolute `given` is
/// an explicit choice and passes. The error is the folder (canonical where it exists).
pub fn stays_inside(folder: &Path, given: &Path) -> Result<(), PathBuf> {
    use std::path::Component;
    if given.is_absolute() {
        return Ok(());
    }
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    let canonical = folder
        .canonicalize()
        .unwrap_or_else(|_| folder.to_path_buf());
    let mut depth = 0usize;
    for c in given.components() {
        match c {
            Component::ParentDir if depth == 0 => return Err(canonical),
            Component::ParentDir => depth -= 1,
            Component::Normal(_) => depth += 1,
            _ => {}
        }
    }
    // The longest existing prefix, with its links resolved, must still lie inside.
    let mut probe = folder.join(given);
    loop {
        if let Ok(real) = probe.canonicalize() {
            return if real.starts_with(&canonical) {
                Ok(())
            } else {
                Err(canonical)
            };
        }
        if !probe.pop() {
            return Ok(());
        }
    }
}

/// The parser's message plus the text it stopped at: "Expected comma" alone does not show that
/// the comma is missing after `2` in `subdivide: 2.5`.
fn syntax_message(code: &str, src: &str, line: usize, col: usize) -> String {
    let rest: String = src
        .lines()
        .nth(line.wrapping_sub(1))
        .map(|l| l.chars().skip(col.saturating_sub(1)).collect())
        .unwrap_or_default();
    let found: String = rest
        .trim_end()
        .chars()
        .take_while(|c| !matches!(c, ',' | ')' | ']' | '}'))
        .take(24)
        .collect();
    // Messages that quote the offending name already say what was found.
    if found.trim().is_empty() || code.contains('`') {
        return code.to_string();
    }
    let before = src
        .lines()
        .nth(line - 1)
        .and_then(|l| l.chars().nth(col.saturating_sub(2)));
    let (found, hint) =
        if found.starts_with(['.', 'e', 'E']) && before.is_some_and(|c| c.is_ascii_digit()) {
            (found, " (this field takes a whole number)")
        } else if before == Some('-') && code.contains("out of bounds") {
            (
                format!("-{found}"),
                " (this field takes a non-negative whole number)",
            )
        } else {
            (found, "")
        };
    format!("{code}, found `{}`{hint}", found.trim())
}

/// Reads, parses and validates a scene file.
pub fn load(path: &Path) -> Result<(Scene, String), SceneError> {
    let file = path.display().to_string();
    let src = read_text(path, "scene", validate::MAX_SCENE_BYTES)?;
    Ok((parse(&file, &src)?, src))
}

/// Reads a text input file (`what` names it in errors) through a cap of `max_bytes`, whatever
/// the file is: a regular file is refused from its size before reading, and every read stops
/// after `max_bytes + 1` bytes (a file that grows, a pipe that never ends). Devices are refused
/// (/dev/zero never ends, a terminal waits for typing); a FIFO is opened without waiting for a
/// writer and read to its end, so that one nobody writes to reads as empty instead of blocking.
/// Locates the first byte that is not UTF-8.
pub fn read_text(path: &Path, what: &str, max_bytes: u64) -> Result<String, SceneError> {
    use std::io::Read;
    let file = path.display().to_string();
    let fail = |line, column, message| SceneError {
        file: file.clone(),
        line,
        column,
        message,
    };
    let meta = std::fs::metadata(path)
        .map_err(|e| fail(None, None, format!("cannot read {what} file: {e}")))?;
    if meta.is_dir() {
        return Err(fail(
            None,
            None,
            format!("cannot read {what} file: it is a directory"),
        ));
    }
    let too_large = |size: String| {
        fail(
            None,
            None,
            format!(
                "{what} file is {size} bytes, above the limit of {max_bytes} bytes (see docs/cli.md)"
            ),
        )
    };
    if meta.is_file() && meta.len() > max_bytes {
        return Err(too_large(meta.len().to_string()));
    }
    let fifo = input_kind(&meta).map_err(|kind| {
        fail(
            None,
            None,
            format!(
                "cannot read {what} file: it is {kind}, not a regular file or a pipe \
                 (save the input to a file first)"
            ),
        )
    })?;
    let f = open_input(path, fifo)
        .map_err(|e| fail(None, None, format!("cannot read {what} file: {e}")))?;
    let mut bytes = Vec::with_capacity(meta.len().min(max_bytes) as usize);
    f.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| fail(None, None, format!("cannot read {what} file: {e}")))?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(format!("more than {max_bytes}")));
    }
    if fifo && bytes.is_empty() {
        return Err(fail(
            None,
            None,
            format!(
                "{what} file is a FIFO with nothing written to it (rodnet does not wait for a \
                 writer: start the writer first, or save the input to a file)"
            ),
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = 1 + good.iter().filter(|&&b| b == b'\n').count();
        let start = good.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1);
        let col = 1 + String::from_utf8_lossy(&good[start..]).chars().count();
        fail(
            Some(line),
            Some(col),
            format!("{what} file is not valid UTF-8 text"),
        )
    })
}

/// Whether an input is a FIFO (`Ok(true)`), another readable kind (`Ok(false)`), or a kind that
/// is refused (`Err` with its name): character and block devices.
fn input_kind(meta: &std::fs::Metadata) -> Result<bool, &'static str> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_char_device() {
            return Err("a character device");
        }
        if t.is_block_device() {
            return Err("a block device");
        }
        Ok(t.is_fifo())
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        Ok(false)
    }
}

/// Opens an input for reading. A FIFO is opened non-blocking (an open for reading otherwise
/// waits for a writer, forever if none comes), then made blocking again so that its data is
/// read to the end the writer gives it: a FIFO without a writer then reads as empty.
fn open_input(path: &Path, fifo: bool) -> std::io::Result<std::fs::File> {
    #[cfg(unix)]
    if fifo {
        use std::os::unix::fs::OpenOptionsExt;
        use std::os::unix::io::AsRawFd;
        let f = std::fs::OpenOptions::new()
            .read(true)
            .custom_flags(libc::O_NONBLOCK)
            .open(path)?;
        let fd = f.as_raw_fd();
        // SAFETY: fcntl on a file descriptor this function owns, with no pointer arguments.
        let ok = unsafe {
            let flags = libc::fcntl(fd, libc::F_GETFL);
            flags >= 0 && libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK) >= 0
        };
        if !ok {
            return Err(std::io::Error::last_os_error());
        }
        return Ok(f);
    }
    let _ = fifo;
    std::fs::File::open(path)
}
