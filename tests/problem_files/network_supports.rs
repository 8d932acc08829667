//! Supports in one direction (`[[network.supports]]`, issue 51) refused with the file, the
//! key and the reason: a direction of zero length, an unknown body, the ground, a support
//! that holds what is held already, and a support in a network with a `[part]`, whose
//! check cannot hold a face in one direction.

use std::path::Path;

use flexopt::problem::Problem;

use crate::network_refused::edited;

const GUIDE: &str = "problems/guide_network.toml";
const LEVER: &str = "problems/lever_network.toml";

/// The edit that adds `support` (its keys) before `[network.input]`.
fn support(keys: &str) -> [(&'static str, String); 1] {
    [(
        "\n[network.input]",
        format!("\n[[network.supports]]\n{keys}\n\n[network.input]"),
    )]
}

fn refused(file: &str, keys: &str, key: &str, words: &[&str]) {
    let [(from, to)] = support(keys);
    crate::network_refused::refused(file, &[(from, &to)], key, words);
}

fn with_support(file: &str, keys: &str) -> String {
    let [(from, to)] = support(keys);
    edited(file, &[(from, &to)])
}

#[test]
fn a_support_is_refused_with_its_key_and_the_reason() {
    let at = "at = [\"L/2\", \"0\"]";
    refused(
        GUIDE,
        &format!("body = \"stage\"\n{at}\ndirection = [\"0\", \"0*2\"]"),
        "network.supports[0].direction",
        &["zero length"],
    );
    refused(
        GUIDE,
        &format!("body = \"slider\"\n{at}\ndirection = [\"1\", \"0\"]"),
        "network.supports[0].body",
        &["unknown body \"slider\"", "\"stage\""],
    );
    refused(
        GUIDE,
        &format!("body = \"ground\"\n{at}\ndirection = [\"1\", \"0\"]"),
        "network.supports[0].body",
        &["the ground does not move"],
    );
    // a key a support does not take, named with the support's
    let text = with_support(
        GUIDE,
        &format!("body = \"stage\"\n{at}\ndirection = [\"1\", \"0\"]\nheld = true"),
    );
    let Err(e) = Problem::parse(Path::new("held.toml"), &text) else {
        panic!("an unknown key is refused")
    };
    let shown = e.to_string();
    assert!(shown.contains("network.supports[0]"), "{shown}");
    assert!(shown.contains("unknown field `held`"), "{shown}");
    refused(
        LEVER,
        "body = \"lever\"\nat = [\"a\", \"0\"]\ndirection = [\"1\", \"0\"]",
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
    // without its [part], which a supported network does not take
    let start = text.find("\n[part]").expect("the guide has a part");
    let end = text[start + 1..]
        .find("\n[")
        .map_or(text.len(), |e| start + 1 + e);
    let text = format!("{}{}", &text[..start], &text[end..]);
    let shown = match Problem::parse(Path::new("held.toml"), &text) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("a redundant support must be refused"),
    };
    assert!(shown.contains("network.supports[1]"), "{shown}");
    assert!(shown.contains("held already"), "{shown}");
}
