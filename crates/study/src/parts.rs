//! The parts of a sharded run on disk: each written atomically beside a small manifest, checked
//! and merged back into the one-machine output byte for byte (see docs/design/shards.md).
//!
//! A part is `DIR/part-IIIII-of-NNNNN.EXT` (zero-padded, so the sorted names are the shards'
//! order) with its [`Manifest`] in `DIR/part-IIIII-of-NNNNN.EXT.manifest.json`. The data is written
//! under a hidden temporary name and renamed when complete; the manifest is renamed into place
//! last, so **a file without a manifest is not a part** (a task killed half way leaves none). Every
//! CSV part starts with the header line (glob readers such as `pandas`/`dask` `read_csv` see a
//! table in each); [`PartSet::merge_into`] keeps the first part's and strips the others', so its output is the
//! unsharded run's output byte for byte.
//!
//! ```
//! use loomkin_study::parts::{self, Manifest, PartWriter};
//! use loomkin_units::Shard;
//! use std::io::Write;
//!
//! let dir = std::env::temp_dir().join(format!("loomkin-parts-doc-{}", std::process::id()));
//! let head = |i| Manifest::head("study-1", vec!["sweep".into()], Shard { index: i, count: 2 });
//! for (i, rows) in [(1, "1\n2\n"), (2, "3\n")] {
//!     let mut w = PartWriter::create(&dir, head(i), "csv")?;
//!     write!(w, "x\n{rows}").unwrap();
//!     w.finish()?;
//! }
//! let set = parts::find(std::slice::from_ref(&dir))?.check()?;
//! let mut out = Vec::new();
//! set.merge_into(&mut out)?;
//! assert_eq!(out, b"x\n1\n2\n3\n");
//! # std::fs::remove_dir_all(&dir).unwrap();
//! # Ok::<(), loomkin_study::parts::PartError>(())
//! ```

use loomkin_units::Shard;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{self, BufRead, BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The `format` of every manifest this version writes.
pub const FORMAT: &str = "loomkin-part/1";

/// Ending of a manifest's file name (after the part's own name).
pub const MANIFEST_SUFFIX: &str = ".manifest.json";

/// What went wrong with a part or a set of parts.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum PartError {
    /// A set of parts that does not make one complete run: a part missing, incomplete, from
    /// another study (the check of [`Found::check`]; a run failure, exit code 1).
    #[error("{0}")]
    Check(String),
    /// A file that cannot be read or written (exit code 1).
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: io::Error,
    },
    /// Input that is not what the command reads: no manifest, a draw of another seed, a line that
    /// is not a row (the user's mistake, exit code 2).
    #[error("{0}")]
    Input(String),
}

impl PartError {
    fn io(path: &Path, source: io::Error) -> Self {
        Self::Io { path: path.display().to_string(), source }
    }

    /// Whether this is the user's input rather than a failed run or check (exit code 2, not 1).
    pub fn is_input(&self) -> bool {
        matches!(self, Self::Input(_))
    }
}

/// Result alias of this module.
pub type Result<T, E = PartError> = std::result::Result<T, E>;

/// The 64-bit FNV-1a hash: the checksum of a part and the fingerprint of a study. Not a
/// cryptographic hash: it catches a truncated, mixed-up or damaged file, not a forged one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fnv64(u64);

impl Default for Fnv64 {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv64 {
    /// Adds bytes.
    pub fn update(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// The hash as 16 hexadecimal digits.
    pub fn hex(&self) -> String {
        format!("{:016x}", self.0)
    }

    /// The hash of `bytes`, as [`Fnv64::hex`].
    pub fn of(bytes: &[u8]) -> String {
        let mut h = Self::default();
        h.update(bytes);
        h.hex()
    }
}

/// A fact for a manifest ([`Manifest::facts`]): `value` as compact JSON.
pub fn fact(value: &impl Serialize) -> String {
    serde_json::to_string(value).unwrap_or_else(|e| format!("(not serialisable: {e})"))
}

/// A fingerprint for a manifest: the [`Fnv64`] of `value`'s compact JSON (for a value too large
/// to quote, such as a model).
pub fn fingerprint(value: &impl Serialize) -> String {
    Fnv64::of(fact(value).as_bytes())
}

/// What a part says about itself, written beside it as JSON.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// [`FORMAT`].
    pub format: String,
    /// Fingerprint of the study: every part of one run has the same (the command line without
    /// its shard and its input files' contents).
    pub study: String,
    /// The command line that made the part, without `--shard` and the part directory.
    pub command: Vec<String>,
    /// Which shard this is.
    pub shard: Shard,
    /// What a reduce checks before it reads the rows (a Monte-Carlo study: `seed`, `draws`,
    /// `inputs` — the drawn distributions — and `model`).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub facts: BTreeMap<String, String>,
    /// The part's header line (CSV, without its newline); `None` for JSON Lines.
    pub header: Option<String>,
    /// Rows (lines after the header).
    pub rows: u64,
    /// Size of the part in bytes.
    pub bytes: u64,
    /// [`Fnv64`] of the part's bytes.
    pub checksum: String,
}

impl Manifest {
    /// The part of a manifest known before the rows are written (`rows`, `bytes`, `checksum`
    /// and `header` are set by [`PartWriter::finish`]).
    pub fn head(study: &str, command: Vec<String>, shard: Shard) -> Self {
        Self {
            format: FORMAT.into(),
            study: study.into(),
            command,
            shard,
            facts: BTreeMap::new(),
            header: None,
            rows: 0,
            bytes: 0,
            checksum: String::new(),
        }
    }

    /// Reads a manifest file.
    pub fn read(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| PartError::io(path, e))?;
        let m: Self = serde_json::from_str(&text)
            .map_err(|e| PartError::Input(format!("{}: not a part manifest: {e}", path.display())))?;
        if m.format != FORMAT {
            return Err(PartError::Input(format!(
                "{}: manifest format '{}', this loomkin reads '{FORMAT}'",
                path.display(),
                m.format
            )));
        }
        if m.shard.count == 0 || m.shard.index == 0 || m.shard.index > m.shard.count {
            return Err(PartError::Input(format!(
                "{}: shard {}/{} is not I/N with 1 ≤ I ≤ N",
                path.display(),
                m.shard.index,
                m.shard.count
            )));
        }
        Ok(m)
    }

    /// Writes the manifest to `path` atomically (a temporary name, then renamed).
    pub fn write(&self, path: &Path) -> Result<()> {
        let tmp = hidden_tmp(path);
        let text = serde_json::to_string_pretty(self).map_err(|e| PartError::io(path, io::Error::other(e)))?;
        std::fs::write(&tmp, text + "\n").map_err(|e| PartError::io(&tmp, e))?;
        std::fs::rename(&tmp, path).map_err(|e| PartError::io(path, e))
    }
}

/// The file name of shard `shard`'s part with extension `ext` (`csv`, `jsonl`).
pub fn part_name(shard: Shard, ext: &str) -> String {
    let width = shard.count.to_string().len().max(5);
    format!("part-{:0width$}-of-{:0width$}.{ext}", shard.index, shard.count)
}

/// The manifest's path of the part at `path`.
pub fn manifest_path(path: &Path) -> PathBuf {
    let mut s = path.as_os_str().to_owned();
    s.push(MANIFEST_SUFFIX);
    PathBuf::from(s)
}

/// A hidden temporary name beside `path`, unique to this process.
fn hidden_tmp(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

/// A part being written: bytes go to a hidden temporary file and are counted and hashed; the
/// part and its manifest appear only at [`PartWriter::finish`]. Dropped unfinished (an error on
/// the way), it removes its temporary file: a failed shard leaves no part behind.
pub struct PartWriter {
    path: PathBuf,
    tmp: PathBuf,
    file: Option<BufWriter<File>>,
    hash: Fnv64,
    bytes: u64,
    lines: u64,
    /// The first line as written (up to its newline): a CSV part's header.
    first: Vec<u8>,
    csv: bool,
    manifest: Manifest,
}

impl PartWriter {
    /// Starts the part of `manifest.shard` in `dir` (made if missing), named with `ext`: `csv` (a
    /// table whose first line is its header) or another (`jsonl`: no header). Refuses a directory
    /// that holds parts of another study or of another number of shards: one directory per study.
    pub fn create(dir: &Path, manifest: Manifest, ext: &str) -> Result<Self> {
        std::fs::create_dir_all(dir).map_err(|e| PartError::io(dir, e))?;
        for (path, other) in manifests_in(dir)? {
            if other.study != manifest.study || other.shard.count != manifest.shard.count {
                return Err(PartError::Input(format!(
                    "{} holds parts of another run ({}, {} shards: {}); give each study its own directory",
                    dir.display(),
                    path.display(),
                    other.shard.count,
                    other.command.join(" ")
                )));
            }
        }
        let path = dir.join(part_name(manifest.shard, ext));
        let tmp = hidden_tmp(&path);
        let file = File::create(&tmp).map_err(|e| PartError::io(&tmp, e))?;
        Ok(Self {
            path,
            tmp,
            file: Some(BufWriter::with_capacity(1 << 16, file)),
            hash: Fnv64::default(),
            bytes: 0,
            lines: 0,
            first: Vec::new(),
            csv: ext == "csv",
            manifest,
        })
    }

    /// Where the part will be.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Sets a fact of the manifest (see [`Manifest::facts`]).
    pub fn fact(&mut self, key: &str, value: impl Into<String>) {
        self.manifest.facts.insert(key.into(), value.into());
    }

    /// Completes the part: flushed to disk, renamed into place, then its manifest written (with
    /// the header line of a CSV part).
    pub fn finish(mut self) -> Result<Manifest> {
        let header = (self.csv && self.lines > 0).then(|| String::from_utf8_lossy(&self.first).into_owned());
        let mut file = self.file.take().expect("finished once");
        file.flush().map_err(|e| PartError::io(&self.tmp, e))?;
        file.get_ref().sync_all().map_err(|e| PartError::io(&self.tmp, e))?;
        drop(file);
        let mut m = self.manifest.clone();
        m.rows = self.lines - u64::from(header.is_some() && self.lines > 0);
        m.header = header;
        m.bytes = self.bytes;
        m.checksum = self.hash.hex();
        let manifest = manifest_path(&self.path);
        // The old manifest goes first: between the two renames the part has none (not a part),
        // never an old manifest over new data.
        match std::fs::remove_file(&manifest) {
            Err(e) if e.kind() != io::ErrorKind::NotFound => return Err(PartError::io(&manifest, e)),
            _ => {}
        }
        std::fs::rename(&self.tmp, &self.path).map_err(|e| PartError::io(&self.path, e))?;
        m.write(&manifest)?;
        Ok(m)
    }
}

impl Write for PartWriter {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let file = self.file.as_mut().ok_or_else(|| io::Error::other("part already finished"))?;
        file.write_all(buf)?;
        if self.lines == 0 {
            let end = buf.iter().position(|&b| b == b'\n').unwrap_or(buf.len());
            self.first.extend_from_slice(&buf[..end]);
        }
        self.hash.update(buf);
        self.bytes += buf.len() as u64;
        self.lines += buf.iter().filter(|&&b| b == b'\n').count() as u64;
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.file.as_mut().map_or(Ok(()), |f| f.flush())
    }
}

impl Drop for PartWriter {
    fn drop(&mut self) {
        if self.file.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Standard input copied to a temporary file (removed when dropped), for a reduce that reads its
/// input more than once.
pub struct Spool {
    path: PathBuf,
}

impl Spool {
    /// Copies `reader` to a new temporary file.
    pub fn from_reader(mut reader: impl Read) -> Result<Self> {
        let path = std::env::temp_dir().join(format!("loomkin-stdin-{}.csv", std::process::id()));
        let spool = Self { path };
        let mut file = BufWriter::new(File::create(&spool.path).map_err(|e| PartError::io(&spool.path, e))?);
        io::copy(&mut reader, &mut file).map_err(|e| PartError::io(Path::new("standard input"), e))?;
        file.flush().map_err(|e| PartError::io(&spool.path, e))?;
        Ok(spool)
    }

    /// The file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for Spool {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// The rows of a table, wherever they are: the checked parts of a sharded run, CSV files without
/// manifests (the shards' standard outputs, in order: the first starts with the header, a later
/// one may repeat it), or standard input (`-`).
pub enum Lines {
    /// Parts with manifests.
    Parts(PartSet),
    /// Files without manifests.
    Files(Vec<PathBuf>),
    /// Standard input.
    Stdin,
}

impl Lines {
    /// The table named by `inputs`: `-` alone is standard input; files without manifests are read
    /// as they are; anything else must be the complete, checked parts of one run.
    pub fn open(inputs: &[PathBuf]) -> Result<Self> {
        match Self::open_plain(inputs) {
            Some(lines) => Ok(lines),
            None => Ok(Self::Parts(find(inputs)?.check()?)),
        }
    }

    /// Standard input, or files without manifests; `None` when `inputs` name parts.
    fn open_plain(inputs: &[PathBuf]) -> Option<Self> {
        if let [one] = inputs
            && one.as_os_str() == "-"
        {
            return Some(Self::Stdin);
        }
        let plain =
            |p: &PathBuf| p.is_file() && !p.to_string_lossy().ends_with(MANIFEST_SUFFIX) && !manifest_path(p).exists();
        if !inputs.is_empty() && inputs.iter().all(plain) {
            return Some(Self::Files(inputs.to_vec()));
        }
        None
    }

    /// [`Lines::open`], but part files named one by one may be some of one run's parts
    /// ([`Found::check_some`]): the rows of the parts given — what a task's own front reads
    /// (`shed pareto --from DIR/part-00017-of-01000.csv`). A directory still stands for the whole
    /// run: every part of it must be there.
    pub fn open_some(inputs: &[PathBuf]) -> Result<Self> {
        match Self::open_plain(inputs) {
            Some(lines) => Ok(lines),
            None if inputs.iter().any(|p| p.is_dir()) => Ok(Self::Parts(find(inputs)?.check()?)),
            None => Ok(Self::Parts(find(inputs)?.check_some()?)),
        }
    }

    /// Calls `header` with the table's header line, then `row` with each later line (the file
    /// and the line's number in it, for messages), in order. A header line repeated at the top
    /// of a later part or file is skipped; one that differs is refused.
    pub fn for_each(
        &self,
        header: impl FnOnce(&str) -> Result<()>,
        mut row: impl FnMut(&Path, u64, &str) -> Result<()>,
    ) -> Result<()> {
        let mut header = Some(header);
        let mut first_header: Option<String> = None;
        let mut read = |path: &Path, reader: &mut dyn BufRead| -> Result<()> {
            let mut line = String::new();
            let mut n = 0u64;
            loop {
                line.clear();
                if reader.read_line(&mut line).map_err(|e| read_error(path, e))? == 0 {
                    return Ok(());
                }
                n += 1;
                let text = line.strip_suffix('\n').unwrap_or(&line);
                let text = text.strip_suffix('\r').unwrap_or(text);
                if n == 1 {
                    match &first_header {
                        None => {
                            first_header = Some(text.to_string());
                            if let Some(h) = header.take() {
                                h(text)?;
                            }
                            continue;
                        }
                        Some(h) if h == text => continue,
                        Some(_) => {}
                    }
                }
                row(path, n, text)?;
            }
        };
        match self {
            Self::Parts(set) => {
                for k in 0..set.parts().len() {
                    read(&set.parts()[k].path, &mut set.open(k)?)?;
                }
            }
            Self::Files(files) => {
                for f in files {
                    let file = File::open(f).map_err(|e| PartError::io(f, e))?;
                    read(f, &mut BufReader::with_capacity(1 << 16, file))?;
                }
            }
            Self::Stdin => read(Path::new("standard input"), &mut io::stdin().lock())?,
        }
        if first_header.is_none() {
            return Err(PartError::Input("the table is empty: no header line".into()));
        }
        Ok(())
    }
}

/// The manifests in `dir` (not its subdirectories), by path.
fn manifests_in(dir: &Path) -> Result<Vec<(PathBuf, Manifest)>> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(|e| PartError::io(dir, e))? {
        let path = entry.map_err(|e| PartError::io(dir, e))?.path();
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if name.ends_with(MANIFEST_SUFFIX) && !name.starts_with('.') {
            out.push((path.clone(), Manifest::read(&path)?));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(out)
}

/// One part found: its data file and its manifest.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// The data file.
    pub path: PathBuf,
    /// Its manifest.
    pub manifest: Manifest,
}

/// Parts found by [`find`], not yet checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Found {
    parts: Vec<Part>,
    /// Data files named like parts that have no manifest (a task that did not finish).
    orphans: Vec<PathBuf>,
}

/// The parts named by `inputs`: a directory stands for every part in it; a file is a part (its
/// manifest beside it, `FILE.manifest.json`) or a manifest.
pub fn find(inputs: &[PathBuf]) -> Result<Found> {
    let mut parts = Vec::new();
    let mut orphans = Vec::new();
    for input in inputs {
        if input.is_dir() {
            let manifests = manifests_in(input)?;
            for entry in std::fs::read_dir(input).map_err(|e| PartError::io(input, e))? {
                let path = entry.map_err(|e| PartError::io(input, e))?.path();
                let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                if name.starts_with("part-")
                    && !name.ends_with(MANIFEST_SUFFIX)
                    && !manifests.iter().any(|(m, _)| *m == manifest_path(&path))
                {
                    orphans.push(path);
                }
            }
            for (m, manifest) in manifests {
                let s = m.to_string_lossy();
                let path = PathBuf::from(&s[..s.len() - MANIFEST_SUFFIX.len()]);
                parts.push(Part { path, manifest });
            }
        } else {
            let s = input.to_string_lossy();
            let (path, m) = match s.strip_suffix(MANIFEST_SUFFIX) {
                Some(data) => (PathBuf::from(data), input.clone()),
                None => (input.clone(), manifest_path(input)),
            };
            if !m.exists() {
                return Err(PartError::Input(format!(
                    "{}: no manifest ({} is missing): not a part of a sharded run (an unfinished task, or a file made another way)",
                    path.display(),
                    m.display()
                )));
            }
            parts.push(Part { path, manifest: Manifest::read(&m)? });
        }
    }
    orphans.sort();
    Ok(Found { parts, orphans })
}

/// `1-3,7,9-10`: indices as Slurm's `--array` takes them.
pub fn ranges(indices: &[u32]) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut i = 0;
    while i < indices.len() {
        let mut j = i;
        while j + 1 < indices.len() && indices[j + 1] == indices[j] + 1 {
            j += 1;
        }
        out.push(if j == i { indices[i].to_string() } else { format!("{}-{}", indices[i], indices[j]) });
        i = j + 1;
    }
    out.join(",")
}

impl Found {
    /// Checks that the parts are the N parts of one run, each complete: one study, one N, every
    /// index 1…N once, each file present with its manifest's size (the checksum is checked as
    /// the rows are read), one header. The error names the missing parts (as Slurm's `--array`
    /// takes them) and the damaged ones.
    pub fn check(self) -> Result<PartSet> {
        self.check_parts(true)
    }

    /// [`Found::check`] without the demand that every part be present: the parts given (each
    /// complete, one study, one N, one header, none twice), in shard order. For a reduce whose answer
    /// over some parts means something — the Pareto front of the rows they hold — never for a
    /// merge or a report of the whole run.
    pub fn check_some(self) -> Result<PartSet> {
        self.check_parts(false)
    }

    fn check_parts(self, all: bool) -> Result<PartSet> {
        let Some(first) = self.parts.first() else {
            let more = if self.orphans.is_empty() {
                String::new()
            } else {
                format!(" ({} files without a manifest, e.g. {})", self.orphans.len(), self.orphans[0].display())
            };
            return Err(PartError::Check(format!("no parts found{more}")));
        };
        let (study, count) = (first.manifest.study.clone(), first.manifest.shard.count);
        if let Some(other) = self.parts.iter().find(|p| p.manifest.study != study || p.manifest.shard.count != count) {
            return Err(PartError::Check(format!(
                "{} and {} are parts of different runs ({} of {} shards, {} of {}); merge one study at a time",
                first.path.display(),
                other.path.display(),
                first.manifest.command.join(" "),
                count,
                other.manifest.command.join(" "),
                other.manifest.shard.count
            )));
        }
        let mut by_index: Vec<Option<Part>> = vec![None; count as usize];
        for p in self.parts {
            let slot = &mut by_index[p.manifest.shard.index as usize - 1];
            if let Some(q) = slot
                && q.path != p.path
            {
                return Err(PartError::Check(format!(
                    "part {} of {count} given twice ({} and {})",
                    p.manifest.shard.index,
                    q.path.display(),
                    p.path.display()
                )));
            }
            *slot = Some(p);
        }
        let missing: Vec<u32> = (1..=count).filter(|&i| by_index[i as usize - 1].is_none()).collect();
        if all && !missing.is_empty() {
            let which = if missing.len() == 1 { "shard" } else { "shards" };
            let list = ranges(&missing);
            return Err(PartError::Check(format!(
                "{} of {count} parts missing: {which} {list} (rerun: sbatch --array={list} …)",
                missing.len()
            )));
        }
        let parts: Vec<Part> = by_index.into_iter().flatten().collect();
        for p in &parts {
            let len = std::fs::metadata(&p.path).map_err(|e| PartError::io(&p.path, e))?.len();
            if len != p.manifest.bytes {
                return Err(PartError::Check(format!(
                    "{}: {len} bytes where its manifest says {}: incomplete or changed; rerun shard {}",
                    p.path.display(),
                    p.manifest.bytes,
                    p.manifest.shard.index
                )));
            }
            if p.manifest.header != parts[0].manifest.header {
                return Err(PartError::Check(format!(
                    "{}: its header differs from {}'s",
                    p.path.display(),
                    parts[0].path.display()
                )));
            }
        }
        Ok(PartSet { parts })
    }
}

/// The N parts of one run, checked by [`Found::check`], in shard order.
#[derive(Debug, Clone, PartialEq)]
pub struct PartSet {
    parts: Vec<Part>,
}

impl PartSet {
    /// The parts, in shard order.
    pub fn parts(&self) -> &[Part] {
        &self.parts
    }

    /// The first part's manifest (the study's facts, command and header).
    pub fn manifest(&self) -> &Manifest {
        &self.parts[0].manifest
    }

    /// Rows of all the parts.
    pub fn rows(&self) -> u64 {
        self.parts.iter().map(|p| p.manifest.rows).sum()
    }

    /// Opens part `k` (in shard order) for reading, checked against its manifest as it is read:
    /// a part whose bytes do not hash to its checksum fails at its end.
    pub fn open(&self, k: usize) -> Result<BufReader<CheckedPart>> {
        let p = &self.parts[k];
        let inner = File::open(&p.path).map_err(|e| PartError::io(&p.path, e))?;
        let part = CheckedPart { inner, part: p.clone(), hash: Fnv64::default(), bytes: 0 };
        Ok(BufReader::with_capacity(1 << 16, part))
    }

    /// Writes the unsharded output: the first part whole, the others without their header line.
    /// Every part's checksum is verified on the way; gives the bytes written.
    pub fn merge_into(&self, out: &mut impl Write) -> Result<u64> {
        let mut written = 0;
        for k in 0..self.parts.len() {
            let mut r = self.open(k)?;
            if k > 0 && self.parts[k].manifest.header.is_some() {
                let mut line = Vec::new();
                r.read_until(b'\n', &mut line).map_err(|e| read_error(&self.parts[k].path, e))?;
            }
            written += io::copy(&mut r, out).map_err(|e| read_error(&self.parts[k].path, e))?;
        }
        Ok(written)
    }

    /// [`PartSet::merge_into`] the file `out`, atomically (a temporary name, renamed when every
    /// part has been checked and copied), with its manifest beside it: the run as shard 1 of 1.
    pub fn merge_to(&self, out: &Path) -> Result<Manifest> {
        let first = self.manifest();
        let mut m = Manifest::head(&first.study, first.command.clone(), Shard::WHOLE);
        m.facts = first.facts.clone();
        let tmp = hidden_tmp(out);
        let result = (|| {
            let file = File::create(&tmp).map_err(|e| PartError::io(&tmp, e))?;
            let mut w = HashingWriter { inner: BufWriter::with_capacity(1 << 16, file), hash: Fnv64::default() };
            let bytes = self.merge_into(&mut w)?;
            w.inner.flush().map_err(|e| PartError::io(&tmp, e))?;
            m.bytes = bytes;
            m.checksum = w.hash.hex();
            Ok(())
        })();
        if let Err(e) = result {
            let _ = std::fs::remove_file(&tmp);
            return Err(e);
        }
        m.rows = self.rows();
        m.header = first.header.clone();
        let manifest = manifest_path(out);
        let _ = std::fs::remove_file(&manifest);
        std::fs::rename(&tmp, out).map_err(|e| PartError::io(out, e))?;
        m.write(&manifest)?;
        Ok(m)
    }
}

struct HashingWriter<W> {
    inner: W,
    hash: Fnv64,
}

impl<W: Write> Write for HashingWriter<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash.update(&buf[..n]);
        Ok(n)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// A part that does not match its manifest (carried through `io::Error`).
#[derive(Debug)]
struct Damaged(String);

impl std::fmt::Display for Damaged {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Damaged {}

/// A part being read: at its end, its bytes are checked against the manifest's size and
/// checksum; a mismatch is an error of the read (the part was changed or damaged after it was
/// written).
pub struct CheckedPart {
    inner: File,
    part: Part,
    hash: Fnv64,
    bytes: u64,
}

impl CheckedPart {
    /// The part being read.
    pub fn part(&self) -> &Part {
        &self.part
    }
}

impl Read for CheckedPart {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.hash.update(&buf[..n]);
        self.bytes += n as u64;
        let m = &self.part.manifest;
        if n == 0 && !buf.is_empty() && (self.bytes != m.bytes || self.hash.hex() != m.checksum) {
            return Err(io::Error::other(Damaged(format!(
                "{}: does not match its manifest ({} bytes, checksum {}; the manifest says {} bytes, {}): damaged or changed; rerun shard {}",
                self.part.path.display(),
                self.bytes,
                self.hash.hex(),
                m.bytes,
                m.checksum,
                m.shard.index
            ))));
        }
        Ok(n)
    }
}

/// The error of an `io::Error` met while reading a [`CheckedPart`]: a damaged part is a failed
/// check, anything else an I/O failure on `path`.
pub fn read_error(path: &Path, e: io::Error) -> PartError {
    match e.get_ref().and_then(|i| i.downcast_ref::<Damaged>()) {
        Some(d) => PartError::Check(d.0.clone()),
        None => PartError::io(path, e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmpdir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("loomkin-parts-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    fn write_parts(dir: &Path, study: &str, n: u32, rows: &[&str]) {
        for i in 1..=n {
            let shard = Shard { index: i, count: n };
            let mut w = PartWriter::create(dir, Manifest::head(study, vec!["t".into()], shard), "csv").unwrap();
            w.write_all(b"a,b\n").unwrap();
            for r in &rows[shard.items(rows.len())] {
                w.write_all(r.as_bytes()).unwrap();
            }
            w.finish().unwrap();
        }
    }

    /// FNV-1a of the empty string and of "a" (the published test vectors).
    #[test]
    fn fnv_vectors() {
        assert_eq!(Fnv64::of(b""), "cbf29ce484222325");
        assert_eq!(Fnv64::of(b"a"), "af63dc4c8601ec8c");
        assert_eq!(Fnv64::of(b"foobar"), "85944171f73967e8");
    }

    #[test]
    fn merge_is_the_concatenation_at_every_n() {
        let rows: Vec<String> = (0..5).map(|i| format!("{i},{}\n", i * i)).collect();
        let rows: Vec<&str> = rows.iter().map(String::as_str).collect();
        let whole = format!("a,b\n{}", rows.concat());
        for n in [1, 2, 3, 7] {
            let dir = tmpdir(&format!("n{n}"));
            write_parts(&dir, "s", n, &rows);
            let set = find(std::slice::from_ref(&dir)).unwrap().check().unwrap();
            assert_eq!(set.rows(), 5);
            let mut out = Vec::new();
            set.merge_into(&mut out).unwrap();
            assert_eq!(String::from_utf8(out).unwrap(), whole, "n = {n}");
            // Every part reads as a table on its own.
            for p in set.parts() {
                assert!(std::fs::read_to_string(&p.path).unwrap().starts_with("a,b\n"));
            }
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }

    #[test]
    fn missing_damaged_and_foreign_parts_are_named() {
        let rows = ["1,1\n", "2,2\n", "3,3\n", "4,4\n"];
        let dir = tmpdir("bad");
        write_parts(&dir, "s", 4, &rows);
        std::fs::remove_file(manifest_path(&dir.join(part_name(Shard { index: 2, count: 4 }, "csv")))).unwrap();
        std::fs::remove_file(dir.join(part_name(Shard { index: 3, count: 4 }, "csv"))).unwrap();
        std::fs::remove_file(manifest_path(&dir.join(part_name(Shard { index: 3, count: 4 }, "csv")))).unwrap();
        let e = find(std::slice::from_ref(&dir)).unwrap().check().unwrap_err().to_string();
        assert_eq!(e, "2 of 4 parts missing: shards 2-3 (rerun: sbatch --array=2-3 …)");
        // A part cut short: its size is not its manifest's.
        write_parts(&dir, "s", 4, &rows);
        let p4 = dir.join(part_name(Shard { index: 4, count: 4 }, "csv"));
        std::fs::write(&p4, "a,b\n").unwrap();
        let e = find(std::slice::from_ref(&dir)).unwrap().check().unwrap_err().to_string();
        assert!(e.contains("incomplete or changed; rerun shard 4"), "{e}");
        // Same size, other bytes: caught by the checksum as the rows are merged.
        write_parts(&dir, "s", 4, &rows);
        std::fs::write(&p4, "a,b\n9,9\n").unwrap();
        let set = find(std::slice::from_ref(&dir)).unwrap().check().unwrap();
        let e = set.merge_into(&mut Vec::new()).unwrap_err();
        assert!(matches!(e, PartError::Check(_)) && e.to_string().contains("rerun shard 4"), "{e}");
        // Another study cannot write into the directory.
        let m = Manifest::head("other", vec!["u".into()], Shard { index: 1, count: 4 });
        let e = PartWriter::create(&dir, m, "csv").err().unwrap();
        assert!(e.is_input() && e.to_string().contains("give each study its own directory"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_unfinished_part_leaves_nothing() {
        let dir = tmpdir("drop");
        {
            let mut w =
                PartWriter::create(&dir, Manifest::head("s", vec![], Shard { index: 1, count: 1 }), "csv").unwrap();
            w.write_all(b"a\n1\n").unwrap();
        }
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        let e = find(std::slice::from_ref(&dir)).unwrap().check().unwrap_err().to_string();
        assert_eq!(e, "no parts found");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn slurm_ranges() {
        assert_eq!(ranges(&[1, 2, 3, 7, 9, 10]), "1-3,7,9-10");
        assert_eq!(ranges(&[17]), "17");
    }
}
