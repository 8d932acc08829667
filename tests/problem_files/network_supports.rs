//! Supports in one direction (`[[network.supports]]`, issue 51) refused with the file, the
//! key and the reason: a direction of zero length, an unknown body, the ground, a support
//! that holds what is held already, and a support in a network with a `[part]`, whose
//! check cannot hold a face in one direction.

use std::path::Path;

use flexopt::problem::Problem;

const GUIDE: &str = "problems/guide_network.toml";
const LEVER: &str = "problems/lever_network.toml";

/// `file` with `support` (its keys) added before `[network.input]`.
fn with_support(file: &str, support: &str) -> String {
    let text = std::fs::read_to_string(file).unwrap();
    assert!(text.contains("\n[network.input]"), "{file}");
    text.replacen(
        "\n[network.input]",
        &format!("\n[[network.supports]]\n{support}\n\n[network.input]"),
        1,
    )
}

fn refused(text: &str, key: &str, words: &[&str]) {
    let Err(e) = Problem::parse(Path::new("held.toml"), text) else {
        panic!("must be refused: {key}");
    };
    let shown = e.to_string();
    assert_eq!(e.key, key, "{shown}");
    assert!(shown.starts_with("held.toml"), "{shown}");
    assert!(shown.contains(&format!("`{key}`")), "{shown}");
    for w in words {
        assert!(shown.contains(w), "{w:?} missing from: {shown}");
    }
}

#[test]
fn a_support_is_refused_with_its_key_and_the_reason() {
    let at = "at = [\"L/2\", \"0\"]";
    refused(
        &with_support(
            GUIDE,
            &format!("body = \"stage\"\n{at}\ndirection = [\"0\", \"0*2\"]"),
        ),
        "network.supports[0].direction",
        &["zero length"],
    );
    refused(
        &with_support(
            GUIDE,
            &format!("body = \"slider\"\n{at}\ndirection = [\"1\", \"0\"]"),
        ),
        "network.supports[0].body",
        &["unknown body \"slider\"", "\"stage\""],
    );
    refused(
        &with_support(
            GUIDE,
            &format!("body = \"ground\"\n{at}\ndirection = [\"1\", \"0\"]"),
        ),
        "network.supports[0].body",
        &["the ground does not move"],
    );
    refused(
        &with_support(
            GUIDE,
            &format!("body = \"stage\"\n{at}\ndirection = [\"1\", \"0\"]\nheld = true"),
        ),
        "network.supports[0]",
        &["held"],
    );
    refused(
        &with_support(
            LEVER,
            "body = \"lever\"\nat = [\"a\", \"0\"]\ndirection = [\"1\", \"0\"]",
        ),
        "network.supports",
        &[
            "network.supports[0]",
            "remove the [part] section or the supports",
        ],
    );
}

/// A second guide along the first's direction at the same point holds nothing more: named,
/// at the middle of the bounds, by the key of the later one.
#[test]
fn a_support_that_holds_what_is_held_already_is_named() {
    let one = "body = \"stage\"\nat = [\"L/2\", \"0\"]\ndirection = [\"1\", \"0\"]";
    let text = with_support(GUIDE, &format!("{one}\n\n[[network.supports]]\n{one}"));
    let shown = match Problem::parse(Path::new("held.toml"), &text) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("a redundant support must be refused"),
    };
    assert!(shown.contains("network.supports[1]"), "{shown}");
    assert!(shown.contains("held already"), "{shown}");
}
