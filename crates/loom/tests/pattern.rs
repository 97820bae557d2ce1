//! Weave patterns: the example drafts, section errors, lift plans, and a parser proptest.

mod common;
use common::*;
use loomkin_loom::Pattern;
use proptest::prelude::*;

fn raised(p: &Pattern, pick: usize) -> Vec<usize> {
    (0..p.shafts()).filter(|&s| p.is_up(pick, s)).map(|s| s + 1).collect()
}

#[test]
fn the_example_drafts_read() {
    let plain = wif("plain.wif");
    assert_eq!((plain.shafts(), plain.picks()), (2, 2));
    assert_eq!(raised(&plain, 0), vec![1]);
    assert_eq!(raised(&plain, 1), vec![2]);
    assert_eq!(plain.rows(), Pattern::plain(2).unwrap().rows());
    let twill = wif("twill-2-2.wif");
    assert_eq!(raised(&twill, 0), vec![1, 2]);
    assert_eq!(raised(&twill, 3), vec![1, 4]);
    assert_eq!(twill.ends_per_shaft(), Some(&[1, 1, 1, 1][..]));
    let satin = wif("satin-8.wif");
    assert_eq!(satin.picks(), 8);
    for p in 0..8 {
        assert_eq!(raised(&satin, p), vec![(3 * p) % 8 + 1]);
    }
    // Every shaft once per repeat: a satin.
    let mut count = [0; 8];
    for p in 0..8 {
        count[raised(&satin, p)[0] - 1] += 1;
    }
    assert_eq!(count, [1; 8]);
    let t16 = wif("twill-16.wif");
    assert_eq!((t16.shafts(), t16.picks()), (16, 16));
    assert_eq!(raised(&t16, 0), vec![1, 2, 3, 4, 5, 9, 10, 11]);
    let p24 = wif("point-24.wif");
    assert_eq!((p24.shafts(), p24.picks()), (24, 48));
    assert_eq!(raised(&p24, 0), (1..=12).collect::<Vec<_>>());
    assert_eq!(raised(&p24, 47), raised(&p24, 0));
    let lp = Pattern::from_lift_plan(&example("twill-3-1.txt")).unwrap();
    assert_eq!((lp.shafts(), lp.picks()), (4, 4));
    assert_eq!(raised(&lp, 2), vec![1, 3, 4]);
}

fn wif_err(text: &str) -> String {
    Pattern::from_wif(text).unwrap_err().to_string()
}

#[test]
fn sections_that_disagree_are_named() {
    let twill = example("twill-2-2.wif");
    let e = wif_err(&edited(&twill, "[TREADLING]\n1=1", "[TREADLING]\n1=5"));
    assert_eq!(e, "[TREADLING]: line 40: pick 1 uses treadle 5, which [TIEUP] does not tie up");
    let e = wif_err(&edited(&twill, "[TIEUP]\n1=1,2", "[TIEUP]\n1=1,7"));
    assert_eq!(e, "[TIEUP]: line 34: treadle 1 names shaft 7, beyond Shafts = 4 of [WEAVING]");
    let e = wif_err(&edited(&twill, "[THREADING]\n1=1", "[THREADING]\n1=5"));
    assert!(e.starts_with("[THREADING]: line 28: end 1 names shaft 5"), "{e}");
    let e = wif_err(&edited(&twill, "TREADLING=true", "TREADLING=true\nLIFTPLAN=true"));
    assert!(e.starts_with("[CONTENTS]: line 15 announces [LIFTPLAN]"), "{e}");
    let e =
        wif_err(&edited(&twill, "[TIEUP]\n1=1,2\n2=2,3\n3=3,4\n4=4,1\n", "[TIEUP]\n1=1,2\n2=2,3\n3=3,4\n4=4,1\n5=1\n"));
    assert!(e.starts_with("[TIEUP]: line 38: treadle 5 beyond Treadles = 4"), "{e}");
    let e = wif_err(&edited(&twill, "Shafts=4", "Shafts=four"));
    assert!(e.starts_with("[WEAVING]: line 17: Shafts = 'four'"), "{e}");
    let e = wif_err(&twill.replace("[WIF]", "[NOTWIF]"));
    assert!(e.starts_with("[WIF]: missing"), "{e}");
    let e = wif_err(&edited(&twill, "[TREADLING]\n1=1", "[TREADLING]\n1=1\n1=2"));
    assert!(e.starts_with("[TREADLING]: line 41: 1 given twice"), "{e}");
    let e = wif_err(&edited(&twill, "[WEAVING]", "[WEAVING\n"));
    assert!(e.starts_with("line 16: a section header"), "{e}");
    let sat = example("satin-8.wif");
    let e = wif_err(&edited(&sat, "[LIFTPLAN]\n1=1", "[LIFTPLAN]\n1=9"));
    assert!(e.starts_with("[LIFTPLAN]: line"), "{e}");
    assert!(e.contains("pick 1 names shaft 9, beyond Shafts = 8"), "{e}");
}

#[test]
fn sinking_shed_inverts_the_lifts() {
    let twill = example("twill-2-2.wif").replace("Rising Shed=true", "Rising Shed=false");
    let p = Pattern::from_wif(&twill).unwrap();
    assert_eq!(raised(&p, 0), vec![3, 4]);
}

#[test]
fn lift_plan_errors_name_the_line() {
    let e = Pattern::from_lift_plan("1 2\n3 x\n").unwrap_err().to_string();
    assert!(e.starts_with("line 2: 'x' is not a shaft number"), "{e}");
    let e = Pattern::from_lift_plan("# only a comment\n\n").unwrap_err().to_string();
    assert!(e.starts_with("lift plan: no picks"), "{e}");
    assert_eq!(raised(&Pattern::from_lift_plan("-\n2,3\n").unwrap(), 0), Vec::<usize>::new());
}

/// A WIF file of a pattern, through tie-up and treadling (one treadle per distinct row).
fn write_wif(p: &Pattern) -> String {
    let mut rows: Vec<Vec<usize>> = Vec::new();
    let mut treadling = Vec::new();
    for pick in 0..p.picks() {
        let r = raised(p, pick);
        let t = rows.iter().position(|x| *x == r).unwrap_or_else(|| {
            rows.push(r.clone());
            rows.len() - 1
        });
        treadling.push(t + 1);
    }
    let mut s = format!(
        "[WIF]\nVersion=1.1\n[CONTENTS]\nTIEUP=true\nTREADLING=true\n[WEAVING]\nShafts={}\nTreadles={}\n[WEFT]\nThreads={}\n[TIEUP]\n",
        p.shafts(),
        rows.len(),
        p.picks()
    );
    for (t, r) in rows.iter().enumerate() {
        s += &format!("{}={}\n", t + 1, r.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(","));
    }
    s += "[TREADLING]\n";
    for (pick, t) in treadling.iter().enumerate() {
        s += &format!("{}={t}\n", pick + 1);
    }
    s
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// A pattern written as a lift plan and as a WIF (tie-up and treadling) reads back the same.
    #[test]
    fn patterns_read_back(shafts in 1usize..30, rows in prop::collection::vec(prop::collection::vec(any::<bool>(), 30), 1..40)) {
        let mut lifts: Vec<Vec<bool>> = rows.iter().map(|r| r[..shafts].to_vec()).collect();
        // The highest shaft raised somewhere, so the lift plan names as many shafts.
        lifts[0][shafts - 1] = true;
        let p = Pattern::new(shafts, lifts).unwrap();
        prop_assert_eq!(Pattern::from_lift_plan(&p.to_lift_plan()).unwrap(), p.clone());
        let w = Pattern::from_wif(&write_wif(&p)).unwrap();
        prop_assert_eq!(w.rows(), p.rows());
    }

    /// Any text: an answer or an error, never a panic.
    #[test]
    fn any_text_is_answered(text in "(\\[[A-Z]{0,9}\\]?\n|[0-9a-z =,;-]{0,12}\n){0,30}") {
        let _ = Pattern::from_wif(&text);
        let _ = Pattern::from_lift_plan(&text);
        let _ = loomkin_loom::Loom::from_toml(&text);
    }

    /// The example files with one character changed: an answer or an error, never a panic.
    #[test]
    fn mutated_examples_are_answered(pos in 0usize..4000, c in any::<char>(), which in 0usize..4) {
        let name = ["twill-2-2.wif", "point-24.wif", "rapier-loom.toml", "shuttle-loom.toml"][which];
        let mut text: Vec<char> = example(name).chars().collect();
        let at = pos % text.len();
        text[at] = c;
        let text: String = text.into_iter().collect();
        let _ = Pattern::from_wif(&text);
        let _ = Pattern::from_lift_plan(&text);
        if let Ok(loom) = loomkin_loom::Loom::from_toml(&text) {
            prop_assert!(loom.geometry.stroke_m.iter().all(|h| h.is_finite() && *h > 0.0));
        }
    }
}

#[test]
fn a_lift_plan_draft_without_treadles_reads() {
    // Weaving programs write `Treadles=0` for a draft with a lift plan and no treadles (issue 27).
    let text = example("point-24.wif");
    let base = Pattern::from_wif(&text).unwrap();
    let no_treadles = edited(&text, "Shafts=24\n", "Shafts=24\nTreadles=0\n");
    assert_eq!(Pattern::from_wif(&no_treadles).unwrap(), base);
    // A tie-up with no treadles to tie is still refused, naming the treadle.
    let tied = edited(&example("twill-2-2.wif"), "Treadles=4", "Treadles=0");
    assert!(wif_err(&tied).contains("treadle 1 beyond Treadles = 0"), "{}", wif_err(&tied));
    assert!(wif_err(&edited(&text, "Shafts=24\n", "Shafts=24\nTreadles=-1\n")).contains("from 0 to 2560"));
}

#[test]
fn a_wif_in_the_windows_code_page_reads_with_a_note() {
    let text = example("twill-2-2.wif").replace("; 2/2 twill", "; Köper 2/2 — “twill”");
    let utf8 = Pattern::from_wif_bytes(text.as_bytes()).unwrap();
    assert_eq!(utf8.1, None);
    // The same draft saved in Windows-1252, encoded here from the code page's table: ASCII as it is,
    // ö (Latin-1) 0xF6, the em dash 0x97, the curly quotes 0x93 and 0x94.
    let cp1252: Vec<u8> = text
        .chars()
        .map(|c| match c {
            'ö' => 0xF6,
            '—' => 0x97,
            '“' => 0x93,
            '”' => 0x94,
            c if c.is_ascii() => c as u8,
            c => panic!("{c} not in the test's table"),
        })
        .collect();
    assert!(std::str::from_utf8(&cp1252).is_err());
    let (pattern, note) = Pattern::from_wif_bytes(&cp1252).unwrap();
    assert_eq!(note, Some(loomkin_loom::WIF_CODE_PAGE_NOTE));
    assert_eq!(pattern, utf8.0);
    // Decoded back character for character.
    assert_eq!(loomkin_loom::wif_text(&cp1252).0, text);
    // A UTF-8 byte-order mark is dropped.
    let bom = [b"\xEF\xBB\xBF".as_slice(), text.as_bytes()].concat();
    assert_eq!(Pattern::from_wif_bytes(&bom).unwrap(), utf8);
}

#[test]
fn every_command_refuses_the_same_unweavable_pattern() {
    // [WEFT] Threads beyond the treadling's rows: the picks past them raise nothing. Motion (behind
    // torque, stagger, the diagrams) and timing refuse them with one message (issue 27: torque
    // accepted what check refused).
    let text = example("twill-2-2.wif").replace("[WEFT]\nThreads=4", "[WEFT]\nThreads=7");
    let p = Pattern::from_wif(&text).unwrap();
    assert_eq!(p.picks(), 7);
    let loom = rapier();
    let motion = loomkin_loom::Motion::new(&loom, &p).unwrap_err().to_string();
    assert!(motion.contains("pattern pick 5: raises none of the loom's 24 frames"), "{motion}");
    let check = loomkin_loom::check(&loom, &p).unwrap_err().to_string();
    assert_eq!(check, motion);
    assert_eq!(loomkin_loom::check_weavable(&p, 24).unwrap_err().to_string(), motion);
}
