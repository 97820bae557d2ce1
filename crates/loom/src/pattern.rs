//! The weave pattern: which heald frames are up at every pick of the repeat.
//!
//! Read from a WIF file (Weaving Information File 1.1, an INI file: a lift plan, or a tie-up with a
//! treadling) or from a plain lift plan (one line per pick naming the raised shafts). Shafts are
//! numbered from 1 at the front of the loom, the frame nearest the cloth fell.

use crate::{LoomError, Result};
use serde::Serialize;

/// Most shafts a pattern may name (dobbies carry up to 28 frames, Jacquard-like drafts in WIF more).
pub const MAX_SHAFTS: usize = 256;
/// Most picks in a repeat.
pub const MAX_PICKS: usize = 100_000;

/// Which shafts are raised at every pick of the repeat.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Pattern {
    shafts: usize,
    /// `lifts[p][s]`: shaft `s` (0 = front) raised at pick `p`.
    lifts: Vec<Vec<bool>>,
    /// Warp ends threaded on each shaft in the draft (from a WIF `[THREADING]`), if known.
    ends: Option<Vec<usize>>,
}

impl Pattern {
    /// A pattern from its lift rows (`lifts[p][s]`, shaft 0 at the front); every row as long as
    /// `shafts`, at least one pick.
    pub fn new(shafts: usize, lifts: Vec<Vec<bool>>) -> Result<Self> {
        if shafts == 0 || shafts > MAX_SHAFTS {
            return Err(LoomError::pattern("pattern", format!("{shafts} shafts: allowed 1 to {MAX_SHAFTS}")));
        }
        if lifts.is_empty() || lifts.len() > MAX_PICKS {
            return Err(LoomError::pattern("pattern", format!("{} picks: allowed 1 to {MAX_PICKS}", lifts.len())));
        }
        if let Some(p) = lifts.iter().position(|r| r.len() != shafts) {
            return Err(LoomError::pattern(format!("pick {}", p + 1), format!("row is not {shafts} shafts long")));
        }
        Ok(Self { shafts, lifts, ends: None })
    }

    /// Plain weave on `frames` frames: the odd frames (1, 3, …) up at the first pick, the even ones at the second.
    pub fn plain(frames: usize) -> Result<Self> {
        let row = |odd: bool| (0..frames).map(|s| (s % 2 == 0) == odd).collect();
        Self::new(frames, vec![row(true), row(false)])
    }

    /// Number of shafts the pattern names.
    pub fn shafts(&self) -> usize {
        self.shafts
    }

    /// Picks in the repeat.
    pub fn picks(&self) -> usize {
        self.lifts.len()
    }

    /// Whether shaft `shaft` (0 = front) is up at pick `pick` (both wrapped into the repeat; a
    /// shaft beyond the pattern's count is down).
    pub fn is_up(&self, pick: usize, shaft: usize) -> bool {
        shaft < self.shafts && self.lifts[pick % self.lifts.len()][shaft]
    }

    /// The lift rows, `rows()[p][s]`.
    pub fn rows(&self) -> &[Vec<bool>] {
        &self.lifts
    }

    /// Warp ends per shaft in the draft's threading, if the file gave one.
    pub fn ends_per_shaft(&self) -> Option<&[usize]> {
        self.ends.as_deref()
    }

    /// The pattern as a lift plan text (one line per pick, the raised shafts; `-` for none), which
    /// [`Pattern::from_lift_plan`] reads back.
    pub fn to_lift_plan(&self) -> String {
        let mut out = String::new();
        for row in &self.lifts {
            let up: Vec<String> =
                row.iter().enumerate().filter(|(_, u)| **u).map(|(s, _)| (s + 1).to_string()).collect();
            out.push_str(if up.is_empty() { "-" } else { "" });
            out.push_str(&up.join(" "));
            out.push('\n');
        }
        out
    }

    /// Reads a plain lift plan: one line per pick listing the raised shafts (numbers from 1 at the
    /// front, separated by spaces or commas; `-` for a pick with none raised). Blank lines and
    /// text after `#` are ignored. The pattern has as many shafts as the highest one named.
    pub fn from_lift_plan(text: &str) -> Result<Self> {
        let mut picks: Vec<Vec<usize>> = Vec::new();
        for (i, raw) in text.lines().enumerate() {
            let line = raw.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let place = format!("line {}", i + 1);
            if line == "-" {
                picks.push(Vec::new());
            } else {
                picks.push(parse_list(line, &place, "shaft")?);
            }
            if picks.len() > MAX_PICKS {
                return Err(LoomError::pattern(place, format!("more than {MAX_PICKS} picks")));
            }
        }
        if picks.is_empty() {
            return Err(LoomError::pattern("lift plan", "no picks: give one line per pick with the raised shafts"));
        }
        let shafts = picks.iter().flatten().copied().max().unwrap_or(1).max(1);
        let lifts = picks.iter().map(|up| (1..=shafts).map(|s| up.contains(&s)).collect()).collect();
        Self::new(shafts, lifts)
    }

    /// Reads a WIF file from its bytes as a file holds them: UTF-8 (a byte-order mark dropped), or,
    /// when the bytes are not UTF-8, Windows-1252 — the code page of the Windows weaving programs
    /// that write most WIF files (WIF 1.1 names no encoding; its examples are plain ASCII, which
    /// both read alike). Returns the pattern and, when the fallback was taken, a note saying so
    /// ([`WIF_CODE_PAGE_NOTE`]) for the front end to show. Every front end reads a WIF this way.
    pub fn from_wif_bytes(bytes: &[u8]) -> Result<(Self, Option<&'static str>)> {
        let (text, note) = wif_text(bytes);
        Ok((Self::from_wif(&text)?, note))
    }

    /// Reads a WIF 1.1 file. The lift at each pick comes from `[LIFTPLAN]` if the file has one,
    /// else from `[TREADLING]` through `[TIEUP]`; `Rising Shed=false` in `[WEAVING]` turns the
    /// listed shafts into the lowered ones. `[THREADING]`, if present, gives the ends per shaft.
    ///
    /// Errors name the section: a treadle used in `[TREADLING]` but not tied up in `[TIEUP]`, a
    /// shaft beyond `Shafts` of `[WEAVING]`, a section that `[CONTENTS]` announces but the file
    /// lacks, a line that is not `key=value`.
    pub fn from_wif(text: &str) -> Result<Self> {
        let ini = Ini::parse(text)?;
        if ini.section("WIF").is_none() {
            return Err(LoomError::pattern("[WIF]", "missing: not a WIF file (it must have a [WIF] section)"));
        }
        if let Some(contents) = ini.section("CONTENTS") {
            for (key, value, line) in contents {
                if is_true(value) && ini.section(&key.to_ascii_uppercase()).is_none() {
                    return Err(LoomError::pattern(
                        "[CONTENTS]",
                        format!(
                            "line {line} announces [{}] but the file has no such section",
                            key.to_ascii_uppercase()
                        ),
                    ));
                }
            }
        }
        let weaving =
            ini.section("WEAVING").ok_or_else(|| LoomError::pattern("[WEAVING]", "missing: it must give Shafts"))?;
        let shafts = match ini.get("WEAVING", "shafts") {
            Some((v, line)) => parse_count(v, "[WEAVING]", line, "Shafts", MAX_SHAFTS)?,
            None => return Err(LoomError::pattern("[WEAVING]", "Shafts missing")),
        };
        let treadles = match ini.get("WEAVING", "treadles") {
            // 0: a lift-plan draft with no treadles, as weaving programs write it.
            Some((v, line)) => Some(parse_count_from(v, "[WEAVING]", line, "Treadles", 0, 10 * MAX_SHAFTS)?),
            None => None,
        };
        let rising = match weaving.iter().find(|(k, _, _)| k == "rising shed") {
            Some((_, v, _)) if is_true(v) => true,
            Some((_, v, _)) if is_false(v) => false,
            Some((_, v, line)) => {
                return Err(LoomError::pattern(
                    "[WEAVING]",
                    format!("line {line}: Rising Shed = '{v}': expected true or false"),
                ));
            }
            None => true,
        };
        let weft_threads = match ini.get("WEFT", "threads") {
            Some((v, line)) => Some(parse_count(v, "[WEFT]", line, "Threads", MAX_PICKS)?),
            None => None,
        };
        let check_shafts = |section: &str, list: &[(usize, Vec<usize>, usize)], what: &str| -> Result<()> {
            for (k, ss, line) in list {
                if let Some(s) = ss.iter().find(|&&s| s > shafts) {
                    return Err(LoomError::pattern(
                        format!("[{section}]"),
                        format!("line {line}: {what} {k} names shaft {s}, beyond Shafts = {shafts} of [WEAVING]"),
                    ));
                }
            }
            Ok(())
        };
        let mut ends = None;
        if let Some(rows) = ini.numbered("THREADING")? {
            check_shafts("THREADING", &rows, "end")?;
            let mut count = vec![0usize; shafts];
            for (_, ss, _) in &rows {
                for s in ss {
                    count[s - 1] += 1;
                }
            }
            ends = Some(count);
        }
        let by_pick: Vec<(usize, Vec<usize>, usize)> = if let Some(rows) = ini.numbered("LIFTPLAN")? {
            check_shafts("LIFTPLAN", &rows, "pick")?;
            rows
        } else {
            let tieup = ini.numbered("TIEUP")?.ok_or_else(|| {
                LoomError::pattern(
                    "[LIFTPLAN]",
                    "missing, and no [TIEUP] with [TREADLING] instead: the file gives no lifts",
                )
            })?;
            check_shafts("TIEUP", &tieup, "treadle")?;
            if let Some(n) = treadles
                && let Some((t, _, line)) = tieup.iter().find(|(t, _, _)| *t > n)
            {
                return Err(LoomError::pattern(
                    "[TIEUP]",
                    format!("line {line}: treadle {t} beyond Treadles = {n} of [WEAVING]"),
                ));
            }
            let treadling = ini
                .numbered("TREADLING")?
                .ok_or_else(|| LoomError::pattern("[TREADLING]", "missing: a [TIEUP] needs a [TREADLING]"))?;
            let mut rows = Vec::with_capacity(treadling.len());
            for (pick, ts, line) in treadling {
                let mut up = Vec::new();
                for t in ts {
                    let tied = tieup.iter().find(|(k, _, _)| *k == t).ok_or_else(|| {
                        LoomError::pattern(
                            "[TREADLING]",
                            format!("line {line}: pick {pick} uses treadle {t}, which [TIEUP] does not tie up"),
                        )
                    })?;
                    up.extend_from_slice(&tied.1);
                }
                rows.push((pick, up, line));
            }
            rows
        };
        let last = by_pick.iter().map(|(p, _, _)| *p).max().unwrap_or(0);
        let picks = weft_threads.unwrap_or(last).max(last);
        if picks == 0 {
            return Err(LoomError::pattern("[LIFTPLAN]", "no picks"));
        }
        if picks > MAX_PICKS {
            return Err(LoomError::pattern("[WEFT]", format!("{picks} picks: allowed at most {MAX_PICKS}")));
        }
        let mut lifts = vec![vec![!rising; shafts]; picks];
        for (p, ss, _) in by_pick {
            for s in ss {
                lifts[p - 1][s - 1] = rising;
            }
        }
        let mut pattern = Self::new(shafts, lifts)?;
        pattern.ends = ends;
        Ok(pattern)
    }
}

/// The note of a WIF read as Windows-1252 ([`Pattern::from_wif_bytes`]).
pub const WIF_CODE_PAGE_NOTE: &str =
    "the file is not UTF-8 text: read as Windows-1252, the code page Windows weaving programs write";

/// A WIF file's text from its bytes: UTF-8 without its byte-order mark, else Windows-1252 with
/// [`WIF_CODE_PAGE_NOTE`]. Every byte sequence decodes (Windows-1252 maps each byte to a character).
pub fn wif_text(bytes: &[u8]) -> (std::borrow::Cow<'_, str>, Option<&'static str>) {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(text) => (std::borrow::Cow::Borrowed(text), None),
        Err(_) => (encoding_rs::WINDOWS_1252.decode_without_bom_handling(bytes).0, Some(WIF_CODE_PAGE_NOTE)),
    }
}

/// Checks that `pattern` can be woven on a loom of `frames` heald frames: it names no more shafts
/// than the loom has frames, and every pick has warp above and below the carrier (some frame up,
/// some down). The one check of a pattern against a loom: [`crate::Motion::new`] makes it, so every
/// command and front end that moves the frames refuses the same patterns with the same message.
pub fn check_weavable(pattern: &Pattern, frames: usize) -> Result<()> {
    if pattern.shafts() > frames {
        return Err(LoomError::pattern(
            "pattern",
            format!(
                "the draft has {} shafts but the loom has {frames} frames (geometry.frame_distances_mm)",
                pattern.shafts()
            ),
        ));
    }
    for (p, row) in pattern.rows().iter().enumerate() {
        let ups = row.iter().filter(|u| **u).count();
        if ups == 0 || ups == frames {
            return Err(LoomError::pattern(
                format!("pattern pick {}", p + 1),
                format!(
                    "{} of the loom's {frames} frames: a shed needs warp above and below the carrier",
                    if ups == 0 { "raises none" } else { "raises all" }
                ),
            ));
        }
    }
    Ok(())
}

fn is_true(v: &str) -> bool {
    matches!(v.trim().to_ascii_lowercase().as_str(), "true" | "yes" | "on" | "1")
}

fn is_false(v: &str) -> bool {
    matches!(v.trim().to_ascii_lowercase().as_str(), "false" | "no" | "off" | "0")
}

fn parse_count(v: &str, section: &str, line: usize, key: &str, max: usize) -> Result<usize> {
    parse_count_from(v, section, line, key, 1, max)
}

fn parse_count_from(v: &str, section: &str, line: usize, key: &str, min: usize, max: usize) -> Result<usize> {
    match v.trim().parse::<usize>() {
        Ok(n) if (min..=max).contains(&n) => Ok(n),
        _ => Err(LoomError::pattern(
            section,
            format!("line {line}: {key} = '{v}': expected a whole number from {min} to {max}"),
        )),
    }
}

/// A list of positive numbers separated by commas or spaces.
fn parse_list(text: &str, place: &str, what: &str) -> Result<Vec<usize>> {
    let mut out = Vec::new();
    for tok in text.split([',', ' ', '\t']).map(str::trim).filter(|t| !t.is_empty()) {
        match tok.parse::<usize>() {
            Ok(n) if (1..=MAX_SHAFTS * 10).contains(&n) => {
                if !out.contains(&n) {
                    out.push(n);
                }
            }
            _ => {
                return Err(LoomError::pattern(
                    place,
                    format!("'{tok}' is not a {what} number: expected whole numbers from 1 to {}", MAX_SHAFTS * 10),
                ));
            }
        }
    }
    Ok(out)
}

/// A minimal INI reader: `[SECTION]` headers, `key=value` lines, `;` comment lines. Section and
/// key names are compared without case.
struct Ini {
    /// (section name upper-case, its entries).
    sections: Vec<(String, Vec<Entry>)>,
}

/// One `key=value` line: key lower-case, value, line number.
type Entry = (String, String, usize);

impl Ini {
    fn parse(text: &str) -> Result<Self> {
        let mut sections: Vec<(String, Vec<Entry>)> = Vec::new();
        for (i, raw) in text.lines().enumerate() {
            let line = raw.trim().trim_start_matches('\u{feff}');
            let n = i + 1;
            if line.is_empty() || line.starts_with(';') {
                continue;
            }
            if let Some(rest) = line.strip_prefix('[') {
                let Some(name) = rest.strip_suffix(']') else {
                    return Err(LoomError::pattern(format!("line {n}"), "a section header must end with ']'"));
                };
                let name = name.trim().to_ascii_uppercase();
                if sections.iter().any(|(s, _)| *s == name) {
                    return Err(LoomError::pattern(
                        format!("[{name}]"),
                        format!("line {n}: the section appears twice"),
                    ));
                }
                sections.push((name, Vec::new()));
                continue;
            }
            let Some((k, v)) = line.split_once('=') else {
                return Err(LoomError::pattern(
                    format!("line {n}"),
                    "expected key=value, a [SECTION] header or a ; comment",
                ));
            };
            let Some((_, entries)) = sections.last_mut() else {
                return Err(LoomError::pattern(format!("line {n}"), "key=value before any [SECTION] header"));
            };
            entries.push((k.trim().to_ascii_lowercase(), v.trim().to_string(), n));
        }
        Ok(Self { sections })
    }

    fn section(&self, name: &str) -> Option<&[(String, String, usize)]> {
        self.sections.iter().find(|(s, _)| s == name).map(|(_, e)| e.as_slice())
    }

    fn get(&self, section: &str, key: &str) -> Option<(&str, usize)> {
        self.section(section)?.iter().find(|(k, _, _)| k == key).map(|(_, v, l)| (v.as_str(), *l))
    }

    /// A section of `number=list` lines (threading, tie-up, treadling, lift plan), or `None` if absent.
    #[allow(clippy::type_complexity)]
    fn numbered(&self, name: &str) -> Result<Option<Vec<(usize, Vec<usize>, usize)>>> {
        let Some(entries) = self.section(name) else { return Ok(None) };
        let section = format!("[{name}]");
        let mut out: Vec<(usize, Vec<usize>, usize)> = Vec::with_capacity(entries.len());
        let mut seen = std::collections::HashSet::with_capacity(entries.len());
        for (k, v, line) in entries {
            let key = match k.parse::<usize>() {
                Ok(n) if (1..=MAX_PICKS).contains(&n) => n,
                _ => {
                    return Err(LoomError::pattern(
                        &section,
                        format!("line {line}: key '{k}' is not a number from 1 to {MAX_PICKS}"),
                    ));
                }
            };
            if !seen.insert(key) {
                return Err(LoomError::pattern(&section, format!("line {line}: {key} given twice")));
            }
            let list = if v.is_empty() {
                Vec::new()
            } else {
                parse_list(v, &format!("{section} line {line}"), "shaft or treadle")?
            };
            out.push((key, list, *line));
        }
        Ok(Some(out))
    }
}
