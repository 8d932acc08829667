//! Issue 28, item 1: `report.html`, the set as one self-contained page. The page embeds every
//! picture of the set and fetches nothing; headless Chromium (Debian package `chromium`,
//! installed by `.ci/run`) loads it, and a check added to a copy of it finds every picture
//! decoded and no element wider than its box, at a screen's width and at an A4 page's.
//! Without Chromium that part fails under CI (the variable `CI` set) and says so elsewhere.

use std::path::{Path, PathBuf};
use std::process::Command;

use base64::Engine;

use crate::common::{assert_whole_set, flexopt, flexopt_ok};

const WEI2017: &str = "problems/wei2017.toml";

fn fresh(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexopt-report-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// wei2017's problem with its refinement on, at most 2 FE checks, written into `dir`.
fn refined_problem(dir: &Path) -> String {
    let text = std::fs::read_to_string(WEI2017)
        .unwrap()
        .replacen(
            "# [refine]\n# fidelity = \"fe\"",
            "[refine]\nfidelity = \"fe\"",
            1,
        )
        .replacen("# max_fe = 12", "max_fe = 2", 1);
    assert!(text.contains("max_fe = 2\n"));
    let file = dir.join("w.toml");
    std::fs::write(&file, text).unwrap();
    file.to_str().unwrap().to_string()
}

fn run(file: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["run", file, "--starts", "8", "--quiet", "--out"];
    args.push(out.to_str().unwrap());
    args.extend(extra);
    flexopt(&args)
}

/// The `src` of every `<img>` of `html`.
fn image_sources(html: &str) -> Vec<&str> {
    html.split("<img ")
        .skip(1)
        .map(|tag| {
            let src = tag.split("src=\"").nth(1).expect("an img with a src");
            &src[..src.find('"').unwrap()]
        })
        .collect()
}

fn chromium() -> Option<&'static str> {
    let found = Command::new("chromium")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    crate::common::peer_present(
        found,
        "chromium (Debian package chromium)",
        "the check of report.html in a browser",
    )
    .then_some("chromium")
}

/// Chromium, headless and offline, on `page` with `args` (its profile in `profile`).
fn headless(profile: &Path, page: &Path, width: u32, args: &[&str]) -> std::process::Output {
    crate::common::succeeds(
        Command::new("chromium")
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--hide-scrollbars",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg(format!("--window-size={width},1400"))
            .args(args)
            .arg(format!("file://{}", page.canonicalize().unwrap().display())),
    )
}

/// Runs in the page once it has loaded: each picture's decoded width, and every element
/// whose content is wider than its box (the page's own width included), written into the
/// body for `--dump-dom` to show.
const CHECK: &str = r#"<script>
window.addEventListener('load', () => {
  const over = [...document.querySelectorAll('body, body *')]
    .filter(e => e.clientWidth > 0 && e.scrollWidth > e.clientWidth + 1)
    .map(e => e.tagName + (e.id ? '#' + e.id : '') + ': ' + e.scrollWidth + ' > ' + e.clientWidth);
  if (document.documentElement.scrollWidth > window.innerWidth) over.push('page');
  const widths = [...document.images].map(i => i.complete ? i.naturalWidth : 0);
  const pre = document.createElement('pre');
  pre.id = 'layout-check';
  pre.textContent = JSON.stringify({ widths, over });
  pre.style.display = 'none';
  document.body.appendChild(pre);
});
</script>"#;

/// The check's result in the DOM Chromium dumps.
fn layout_check(dom: &str) -> serde_json::Value {
    let start = dom.find("id=\"layout-check\"").expect("the check ran");
    let text = &dom[start..];
    let text = &text[text.find('>').unwrap() + 1..text.find("</pre>").unwrap()];
    let text = text
        .replace("&quot;", "\"")
        .replace("&gt;", ">")
        .replace("&lt;", "<")
        .replace("&amp;", "&");
    serde_json::from_str(&text).unwrap()
}

/// `run --verify --report` of a refined problem: one page of the whole set (the problem as
/// stated, the optimum, each constraint, the part with its plate thickness, the FE check with
/// the column to read, the refinement, every file with its hash), its pictures the set's own
/// PNGs, nothing fetched; Chromium shows every picture and no element overflows its box, at
/// 1100 px and at 794 px (A4 at 96 dpi), and prints it to a PDF.
#[test]
fn run_report_is_one_self_contained_page_of_the_set_that_chromium_shows_whole() {
    let dir = fresh("page");
    let file = refined_problem(&dir);
    let out = dir.join("out");
    let ran = run(&file, &out, &["--verify", "--report"]);
    // the refinement may stop at its 2 FE checks (exit 3 or 4): its files are written
    assert!(matches!(ran.status.code(), Some(0 | 3 | 4)), "{ran:?}");
    let listed = assert_whole_set(&out, &[]);
    assert!(listed.iter().any(|n| n == "report.html"), "{listed:?}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();

    // self-contained: no script, nothing fetched, every picture a PNG of the set
    assert!(!html.contains("<script"), "a script in the report");
    for scheme in ["http:", "https:", "//", "file:"] {
        assert!(!html.contains(&format!("src=\"{scheme}")), "{scheme}");
        assert!(!html.contains(&format!("href=\"{scheme}")), "{scheme}");
    }
    assert!(!html.contains("url("), "the stylesheet fetches something");
    let sources = image_sources(&html);
    let pictures = [
        "zones.png",
        "configurations.png",
        "part.png",
        "verify/stress.png",
        "verify/deformed.png",
        "refined_part.png",
    ];
    assert_eq!(sources.len(), pictures.len(), "{}", sources.len());
    for (src, name) in sources.iter().zip(pictures) {
        let data = src
            .strip_prefix("data:image/png;base64,")
            .unwrap_or_else(|| panic!("{name}: not an embedded PNG"));
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(data)
            .unwrap();
        assert_eq!(bytes, std::fs::read(out.join(name)).unwrap(), "{name}");
    }

    // what a review needs, from the set's files
    let optimum: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("optimum.json")).unwrap()).unwrap();
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("manifest.json")).unwrap()).unwrap();
    for c in optimum["constraints"].as_array().unwrap() {
        let name = c["output"].as_str().unwrap();
        assert!(html.contains(&format!("<code>{name}</code>")), "{name}");
    }
    for f in manifest["files"].as_array().unwrap() {
        if let (Some(name), Some(hash)) = (f["name"].as_str(), f["fnv1a64"].as_str()) {
            if name != "report.html" {
                assert!(html.contains(hash), "{name}'s hash {hash}");
            }
        }
    }
    let seed = format!("seed {}", optimum["seed"]);
    let needed = [
        "max_fe = 2",             // the problem file as stated
        "Plate thickness",        // the part
        "<strong>10 mm</strong>", // its thickness
        "read the 3D column",     // which FE column to read
        "plane stress",           // every idealization
        "plane strain",
        "Refinement against the part", // the refinement
        "verify/verify.json",          // the check's files, listed
        &seed,
        concat!("flexopt ", env!("CARGO_PKG_VERSION")),
        "@media print",
    ];
    for n in needed {
        assert!(html.contains(n), "the report lacks {n:?}");
    }

    let Some(_) = chromium() else {
        return;
    };
    let checked = dir.join("checked.html");
    std::fs::write(
        &checked,
        html.replace("</body>", &format!("{CHECK}</body>")),
    )
    .unwrap();
    for width in [1100, 794] {
        let dom = headless(
            &dir.join(format!("profile{width}")),
            &checked,
            width,
            &["--dump-dom"],
        );
        let check = layout_check(&String::from_utf8_lossy(&dom.stdout));
        let widths = check["widths"].as_array().unwrap();
        assert_eq!(widths.len(), pictures.len(), "{width} px: {check}");
        assert!(
            widths.iter().all(|w| w.as_u64().unwrap() > 0),
            "{width} px: a picture did not load: {check}"
        );
        assert_eq!(check["over"], serde_json::json!([]), "{width} px: overflow");
    }
    let shot = dir.join("report.png");
    let pdf = dir.join("report.pdf");
    headless(
        &dir.join("profile_shot"),
        &out.join("report.html"),
        1100,
        &[&format!("--screenshot={}", shot.display())],
    );
    headless(
        &dir.join("profile_pdf"),
        &out.join("report.html"),
        1100,
        &[
            "--no-pdf-header-footer",
            &format!("--print-to-pdf={}", pdf.display()),
        ],
    );
    assert!(std::fs::read(&shot).unwrap().starts_with(b"\x89PNG"));
    assert!(std::fs::read(&pdf).unwrap().starts_with(b"%PDF"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The same run gives the same page (no time, no folder name in it), so a committed set
/// with its report regenerates byte-identical.
#[test]
fn the_report_of_the_same_run_is_the_same_bytes() {
    let dir = fresh("same");
    let pages: Vec<Vec<u8>> = ["a", "b"]
        .iter()
        .map(|name| {
            let out = dir.join(name);
            let ran = run(WEI2017, &out, &["--report"]);
            assert!(ran.status.success(), "{ran:?}");
            std::fs::read(out.join("report.html")).unwrap()
        })
        .collect();
    assert!(pages[0] == pages[1], "two runs wrote different reports");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `flexopt report DIR`: adds report.html to the run's set (so the next run into the folder
/// leaves no stale report), states the problem file given with --problem, and refuses what is
/// not a run's folder or not the file the run read (exit 2, naming it and what is wrong),
/// writing nothing.
#[test]
fn report_command_adds_the_page_to_the_set_and_refuses_what_is_not_the_run() {
    let dir = fresh("command");
    let out = dir.join("out");
    assert!(run(WEI2017, &out, &[]).status.success());
    let o = out.to_str().unwrap();
    let said = flexopt_ok(&["report", o, "--problem", WEI2017]);
    assert_eq!(
        String::from_utf8_lossy(&said.stdout).trim(),
        format!("wrote {}", out.join("report.html").display())
    );
    let listed = assert_whole_set(&out, &[]);
    assert!(listed.iter().any(|n| n == "report.html"), "{listed:?}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        html.contains("[[variables]]"),
        "the problem file is not stated"
    );

    // another content of the problem file
    let changed = dir.join("changed.toml");
    let text = std::fs::read_to_string(WEI2017).unwrap();
    std::fs::write(&changed, text.replacen("starts = 300", "starts = 301", 1)).unwrap();
    let before = std::fs::read(out.join("report.html")).unwrap();
    let refused = flexopt(&["report", o, "--problem", changed.to_str().unwrap()]);
    assert_eq!(refused.status.code(), Some(2));
    let message = String::from_utf8_lossy(&refused.stderr);
    assert!(
        message.contains(&format!("{}: key `--problem`", changed.display()))
            && message.contains("not the one this run read"),
        "{message}"
    );
    assert_eq!(std::fs::read(out.join("report.html")).unwrap(), before);

    // a folder that is not a run's: no manifest; a verification's (no optimum.json)
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let refused = flexopt(&["report", empty.to_str().unwrap()]);
    assert_eq!(refused.status.code(), Some(2));
    let message = String::from_utf8_lossy(&refused.stderr);
    assert!(
        message.contains(&format!("{}: no manifest.json", empty.display())),
        "{message}"
    );
    assert!(!empty.join("report.html").exists());
    let check = dir.join("check");
    flexopt_ok(&[
        "verify",
        WEI2017,
        "--optimum",
        out.join("optimum.json").to_str().unwrap(),
        "--out",
        check.to_str().unwrap(),
        "--no-3d",
        "--tolerance",
        "0.05",
    ]);
    let refused = flexopt(&["report", check.to_str().unwrap()]);
    assert_eq!(refused.status.code(), Some(2));
    let message = String::from_utf8_lossy(&refused.stderr);
    assert!(message.contains("lists no optimum.json"), "{message}");
    assert!(!check.join("report.html").exists());

    // the next run without --report takes the page away with the rest of the earlier set
    assert!(run(WEI2017, &out, &[]).status.success());
    let listed = assert_whole_set(&out, &[]);
    assert!(!listed.iter().any(|n| n == "report.html"), "{listed:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A tolerance check of the run's optimum beside the run (`tolerance --out DIR/tolerance`,
/// its default): the report shows its yield, each output's spread and the histogram of each
/// constrained output, and lists its files; Chromium shows it whole at A4 width. A check of
/// another design there is named as such, not shown as the optimum's.
#[test]
fn the_report_shows_the_tolerance_check_of_its_optimum_and_only_of_it() {
    let dir = fresh("tolerance");
    let out = dir.join("out");
    assert!(run(WEI2017, &out, &[]).status.success());
    let o = out.to_str().unwrap();
    let check = out.join("tolerance");
    let c = check.to_str().unwrap();
    let optimum = out.join("optimum.json");
    let samples = ["--samples", "2000"];
    flexopt_ok(
        &[
            &[
                "tolerance",
                WEI2017,
                "--optimum",
                optimum.to_str().unwrap(),
                "--out",
                c,
            ][..],
            &samples,
        ]
        .concat(),
    );
    flexopt_ok(&["report", o]);
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let tolerance: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(check.join("tolerance.json")).unwrap())
            .unwrap();
    assert!(html.contains("Machining tolerances and yield"));
    let yield_text = format!(
        "<strong>{:.2} %</strong>",
        100.0 * tolerance["yield"].as_f64().unwrap()
    );
    assert!(html.contains(&yield_text), "no {yield_text}");
    let sources = image_sources(&html);
    let mut histograms = 0;
    for out_ in tolerance["outputs"].as_array().unwrap() {
        let name = out_["name"].as_str().unwrap();
        assert!(html.contains(&format!("<code>{name}</code>")), "{name}");
        if out_["role"] == "constraint" {
            let png = std::fs::read(check.join(format!("histogram_{name}.png"))).unwrap();
            let uri = format!(
                "data:image/png;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(png)
            );
            assert!(sources.contains(&uri.as_str()), "histogram of {name}");
            histograms += 1;
        }
    }
    assert_eq!(histograms, 5);
    let listed: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(check.join("manifest.json")).unwrap())
            .unwrap();
    for f in listed["files"].as_array().unwrap() {
        if let Some(hash) = f["fnv1a64"].as_str() {
            assert!(html.contains(hash), "{f}");
        }
    }
    if chromium().is_some() {
        let checked = dir.join("checked.html");
        std::fs::write(
            &checked,
            html.replace("</body>", &format!("{CHECK}</body>")),
        )
        .unwrap();
        let dom = headless(&dir.join("profile"), &checked, 794, &["--dump-dom"]);
        let seen = layout_check(&String::from_utf8_lossy(&dom.stdout));
        let widths = seen["widths"].as_array().unwrap();
        assert_eq!(widths.len(), sources.len(), "{seen}");
        assert!(widths.iter().all(|w| w.as_u64().unwrap() > 0), "{seen}");
        assert_eq!(seen["over"], serde_json::json!([]), "overflow");
    }

    // the check of another design in the same folder
    let other = "l2=2,delta2=4,t2=0.4,l3=8,delta3=4,l4=2,delta4=4,t4=0.4";
    flexopt_ok(
        &[
            &["tolerance", WEI2017, "--design", other, "--out", c][..],
            &samples,
        ]
        .concat(),
    );
    flexopt_ok(&["report", o]);
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("tolerance check of another design than this optimum"));
    assert!(
        !html.contains("histogram_"),
        "another design's histograms shown"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A robust run's report puts its optimum beside the nominal one, as `robust.json` holds
/// them: both objectives, both yields, the margins in standard deviations.
#[test]
fn a_robust_runs_report_shows_both_optima_and_their_yields() {
    let dir = fresh("robust");
    let text = std::fs::read_to_string(WEI2017).unwrap();
    let file = dir.join("robust.toml");
    std::fs::write(
        &file,
        text.replace("[search]\n", "[search]\nrobust = { yield = 0.99 }\n"),
    )
    .unwrap();
    let out = dir.join("out");
    let ran = run(file.to_str().unwrap(), &out, &["--report"]);
    assert!(ran.status.success(), "{ran:?}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let robust: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("robust.json")).unwrap()).unwrap();
    assert!(html.contains("The robust optimum beside the nominal one"));
    assert!(html.contains("for a yield of 99.00 %"));
    for side in ["nominal", "robust"] {
        let y = format!("{:.2} %", 100.0 * robust[side]["yield"].as_f64().unwrap());
        assert!(html.contains(&y), "{side}'s yield {y}");
        let margins = robust[side]["margins_in_sigma"].as_object().unwrap();
        assert!(!margins.is_empty());
    }
    for name in robust["robust"]["margins_in_sigma"]
        .as_object()
        .unwrap()
        .keys()
    {
        assert!(
            html.contains(&format!("margin of <code>{name}</code>")),
            "{name}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
