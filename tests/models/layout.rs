//! The layout of `src/` read as text: no import cycle between its top-level modules, and no
//! model's name outside `src/model/` (docs/architecture.md, "Layers"). Comments and doc comments are
//! ignored; the findings name the file and line of each reference.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// A `.rs` file of `src/`: its path relative to the package root and its text.
pub(crate) struct Source {
    pub(crate) path: String,
    pub(crate) text: String,
}

pub(crate) fn sources() -> Vec<Source> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut paths = Vec::new();
    walk(&root.join("src"), &mut paths);
    paths.sort();
    paths
        .into_iter()
        .map(|p| Source {
            text: fs::read_to_string(&p).unwrap(),
            path: p
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/"),
        })
        .collect()
}

/// A string literal's content and the line it starts on.
pub(crate) struct Literal {
    pub(crate) line: usize,
    pub(crate) content: String,
}

/// The code with comments and the contents of string and character literals blanked (lines
/// kept), and the string literals apart.
pub(crate) fn lex(text: &str) -> (String, Vec<Literal>) {
    let c: Vec<char> = text.chars().collect();
    let mut code = String::with_capacity(text.len());
    let mut literals = Vec::new();
    let mut line = 1;
    let mut i = 0;
    let ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    // blanks c[from..to] into `code`, keeping newlines
    let blank = |code: &mut String, line: &mut usize, from: usize, to: usize| {
        for &ch in &c[from..to] {
            if ch == '\n' {
                *line += 1;
                code.push('\n');
            } else {
                code.push(' ');
            }
        }
    };
    while i < c.len() {
        let prev_ident = i > 0 && ident(c[i - 1]);
        if c[i] == '/' && c.get(i + 1) == Some(&'/') {
            let end = (i..c.len()).find(|&j| c[j] == '\n').unwrap_or(c.len());
            blank(&mut code, &mut line, i, end);
            i = end;
        } else if c[i] == '/' && c.get(i + 1) == Some(&'*') {
            let (mut j, mut depth) = (i + 2, 1);
            while j < c.len() && depth > 0 {
                if c[j] == '/' && c.get(j + 1) == Some(&'*') {
                    depth += 1;
                    j += 2;
                } else if c[j] == '*' && c.get(j + 1) == Some(&'/') {
                    depth -= 1;
                    j += 2;
                } else {
                    j += 1;
                }
            }
            blank(&mut code, &mut line, i, j.min(c.len()));
            i = j;
        } else if c[i] == 'r' && !prev_ident && matches!(c.get(i + 1), Some('"') | Some('#')) && {
            let hashes = c[i + 1..].iter().take_while(|&&ch| ch == '#').count();
            c.get(i + 1 + hashes) == Some(&'"')
        } {
            // raw string r"..." / r#"..."#
            let hashes = c[i + 1..].iter().take_while(|&&ch| ch == '#').count();
            let start = i + 2 + hashes;
            let mut j = start;
            while j < c.len()
                && !(c[j] == '"'
                    && c[j + 1..]
                        .iter()
                        .take(hashes)
                        .filter(|&&ch| ch == '#')
                        .count()
                        == hashes)
            {
                j += 1;
            }
            code.push('"');
            let l = line;
            literals.push(Literal {
                line: l,
                content: c[start..j.min(c.len())].iter().collect(),
            });
            blank(&mut code, &mut line, i + 1, j.min(c.len()));
            code.push('"');
            i = (j + 1 + hashes).min(c.len());
        } else if c[i] == '"' {
            let mut j = i + 1;
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            let end = j.min(c.len());
            literals.push(Literal {
                line,
                content: c[i + 1..end].iter().collect(),
            });
            code.push('"');
            blank(&mut code, &mut line, i + 1, end);
            code.push('"');
            i = end + 1;
        } else if c[i] == '\'' {
            // a character literal, or a lifetime or label (left as it is)
            let end = if c.get(i + 1) == Some(&'\\') {
                (i + 2..c.len()).find(|&j| c[j] == '\'')
            } else if c.get(i + 2) == Some(&'\'') {
                Some(i + 2)
            } else {
                None
            };
            match end {
                Some(end) => {
                    code.push('\'');
                    blank(&mut code, &mut line, i + 1, end);
                    code.push('\'');
                    i = end + 1;
                }
                None => {
                    code.push('\'');
                    i += 1;
                }
            }
        } else {
            if c[i] == '\n' {
                line += 1;
            }
            code.push(c[i]);
            i += 1;
        }
    }
    (code, literals)
}

/// The tokens of blanked code that matter to paths: identifiers (with `$crate`), `::`, and
/// single punctuation characters; each with its line.
pub(crate) fn tokens(code: &str) -> Vec<(String, usize)> {
    let c: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if ch.is_alphanumeric()
            || ch == '_'
            || (ch == '$' && c.get(i + 1).is_some_and(|n| n.is_alphabetic()))
        {
            let start = i;
            i += 1;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push((c[start..i].iter().collect(), line));
        } else if ch == ':' && c.get(i + 1) == Some(&':') {
            out.push(("::".into(), line));
            i += 2;
        } else {
            out.push((ch.to_string(), line));
            i += 1;
        }
    }
    out
}

/// The first identifier of each item of the `{...}` group opening at `tokens[open]`.
pub(crate) fn group_heads(tokens: &[(String, usize)], open: usize) -> Vec<(String, usize)> {
    let mut heads = Vec::new();
    let mut depth = 0;
    let mut expect_head = true;
    for (t, line) in &tokens[open..] {
        match t.as_str() {
            "{" => {
                depth += 1;
                if depth == 1 {
                    expect_head = true;
                }
            }
            "}" => {
                depth -= 1;
                if depth == 0 {
                    break;
                }
            }
            "," if depth == 1 => expect_head = true,
            _ if depth == 1 && expect_head => {
                heads.push((t.clone(), *line));
                expect_head = false;
            }
            _ => {}
        }
    }
    heads
}

/// The names that follow a path prefix ending just before `tokens[at]` (`::` expected there).
fn path_heads(tokens: &[(String, usize)], at: usize) -> Vec<(String, usize)> {
    if tokens.get(at).map(|t| t.0.as_str()) != Some("::") {
        return Vec::new();
    }
    match tokens.get(at + 1) {
        Some((t, _)) if t == "{" => group_heads(tokens, at + 1),
        Some((t, line))
            if t.chars()
                .next()
                .is_some_and(|c| c.is_alphabetic() || c == '_') =>
        {
            vec![(t.clone(), *line)]
        }
        _ => Vec::new(),
    }
}

/// How many `super::` open the path at `tokens[at]`, and where the path goes on after them.
pub(crate) fn supers(tokens: &[(String, usize)], at: usize) -> (usize, usize) {
    let (mut n, mut j) = (0, at);
    while tokens.get(j).is_some_and(|x| x.0 == "super")
        && tokens.get(j + 1).is_some_and(|x| x.0 == "::")
    {
        n += 1;
        j += 2;
    }
    (n, j)
}

/// A reference from one top-level module to another, where it is written.
struct Edge {
    from: String,
    to: String,
    at: String,
}

/// The references between the top-level modules of `src/`: the library's (folders and files
/// next to `lib.rs`, items of `lib.rs` itself as `lib.rs`) and the binary's (`main.rs` and the
/// files it declares as modules, named as files).
fn module_edges(sources: &[Source]) -> (BTreeSet<String>, Vec<Edge>) {
    let declared = |file: &str| -> BTreeSet<String> {
        let text = &sources.iter().find(|s| s.path == file).unwrap().text;
        let t = tokens(&lex(text).0);
        t.windows(3)
            .filter(|w| w[0].0 == "mod" && w[2].0 == ";")
            .map(|w| w[1].0.clone())
            .collect()
    };
    let lib_modules = declared("src/lib.rs");
    let bin_modules = declared("src/main.rs");
    let mut nodes = BTreeSet::new();
    let mut edges = Vec::new();
    for source in sources {
        let rel = source.path.strip_prefix("src/").unwrap();
        let mut path: Vec<String> = rel
            .trim_end_matches(".rs")
            .split('/')
            .map(String::from)
            .collect();
        if path.last().is_some_and(|p| p == "mod") {
            path.pop();
        }
        let bin = rel == "main.rs" || bin_modules.contains(&path[0]);
        if rel == "lib.rs" || rel == "main.rs" {
            path.clear();
        } else if !bin && !lib_modules.contains(&path[0]) {
            continue; // not part of either crate
        }
        // a top-level module's node
        let node = |name: &str, in_bin: bool| -> String {
            if in_bin {
                if bin_modules.contains(name) {
                    format!("{name}.rs")
                } else {
                    "main.rs".to_string()
                }
            } else if lib_modules.contains(name) {
                name.to_string()
            } else {
                "lib.rs".to_string()
            }
        };
        let from = match path.first() {
            Some(top) => node(top, bin),
            None => rel.to_string(),
        };
        if rel == "lib.rs" {
            continue; // the crate root only declares the modules
        }
        nodes.insert(from.clone());
        let t = tokens(&lex(&source.text).0);
        let mut inline: Vec<(String, usize)> = Vec::new(); // inline modules and their depth
        let mut depth = 0;
        for i in 0..t.len() {
            let word = t[i].0.as_str();
            let after_path = i > 0 && t[i - 1].0 == "::";
            let mut targets: Vec<(String, String, usize)> = Vec::new(); // (node, name, line)
            match word {
                "{" => depth += 1,
                "}" => {
                    depth -= 1;
                    if inline.last().is_some_and(|m| m.1 == depth) {
                        inline.pop();
                    }
                }
                "mod" if t.get(i + 2).is_some_and(|n| n.0 == "{") => {
                    inline.push((t[i + 1].0.clone(), depth));
                }
                "crate" | "$crate" if !after_path => {
                    for (name, line) in path_heads(&t, i + 1) {
                        targets.push((node(&name, bin), name, line));
                    }
                }
                "flexopt" if bin && !after_path => {
                    for (name, line) in path_heads(&t, i + 1) {
                        targets.push((node(&name, false), name, line));
                    }
                }
                "super" if !after_path => {
                    let (n, j) = supers(&t, i);
                    let here = path.len() + inline.len();
                    if n > 0 && n == here {
                        for (name, line) in path_heads(&t, j - 1) {
                            targets.push((node(&name, bin), name, line));
                        }
                    }
                }
                _ if rel == "main.rs"
                    && inline.is_empty()
                    && !after_path
                    && bin_modules.contains(word)
                    && t.get(i + 1).is_some_and(|x| x.0 == "::") =>
                {
                    targets.push((node(word, true), word.to_string(), t[i].1));
                }
                _ => {}
            }
            for (to, name, line) in targets {
                if name == "self" || name == "super" || to == from {
                    continue;
                }
                nodes.insert(to.clone());
                edges.push(Edge {
                    from: from.clone(),
                    to,
                    at: format!("{}:{line}", source.path),
                });
            }
        }
    }
    (nodes, edges)
}

/// Every elementary cycle of the graph, each once, starting at its smallest node.
pub(crate) fn cycles(
    nodes: &BTreeSet<String>,
    arrows: &BTreeMap<(String, String), Vec<String>>,
) -> Vec<Vec<String>> {
    let names: Vec<&String> = nodes.iter().collect();
    let index = |n: &String| names.iter().position(|m| *m == n).unwrap();
    let mut next = vec![Vec::new(); names.len()];
    for (from, to) in arrows.keys() {
        next[index(from)].push(index(to));
    }
    fn dfs(
        v: usize,
        start: usize,
        next: &[Vec<usize>],
        path: &mut Vec<usize>,
        out: &mut Vec<Vec<usize>>,
    ) {
        for &w in &next[v] {
            if out.len() >= 1000 {
                return;
            }
            if w == start {
                out.push(path.clone());
            } else if w > start && !path.contains(&w) {
                path.push(w);
                dfs(w, start, next, path, out);
                path.pop();
            }
        }
    }
    let mut found = Vec::new();
    for s in 0..names.len() {
        dfs(s, s, &next, &mut vec![s], &mut found);
    }
    found
        .into_iter()
        .map(|c| c.into_iter().map(|i| names[i].clone()).collect())
        .collect()
}

#[test]
fn no_import_cycle_between_the_folders_of_src() {
    let sources = sources();
    let (nodes, edges) = module_edges(&sources);
    let mut arrows: BTreeMap<(String, String), Vec<String>> = BTreeMap::new();
    for e in edges {
        arrows.entry((e.from, e.to)).or_default().push(e.at);
    }
    let found = cycles(&nodes, &arrows);
    let mut report = String::new();
    for cycle in &found {
        report += &format!("\n{} -> {}\n", cycle.join(" -> "), cycle[0]);
        for k in 0..cycle.len() {
            let (from, to) = (&cycle[k], &cycle[(k + 1) % cycle.len()]);
            let at = &arrows[&(from.clone(), to.clone())];
            let more = if at.len() > 1 {
                format!(" (and {} more)", at.len() - 1)
            } else {
                String::new()
            };
            report += &format!("    {from} -> {to}: {}{more}\n", at[0]);
        }
    }
    assert!(
        found.is_empty(),
        "{} import cycle(s) between the top-level modules of src/:\n{report}",
        found.len()
    );
}

/// The models' names, as they would appear in a path or a problem file.
const MODEL_NAMES: [&str; 3] = ["bridge", "prr3", "pss3"];

#[test]
fn no_model_name_outside_src_model() {
    let mut found = BTreeSet::new();
    for source in sources() {
        if source.path.starts_with("src/model/") {
            continue;
        }
        let (code, literals) = lex(&source.text);
        for (token, line) in tokens(&code) {
            if MODEL_NAMES.contains(&token.as_str()) {
                found.insert(format!("{}:{line}: {token}", source.path));
            }
        }
        for literal in literals {
            let words = literal
                .content
                .split(|c: char| !(c.is_alphanumeric() || c == '_'));
            if words.clone().any(|w| MODEL_NAMES.contains(&w)) {
                found.insert(format!(
                    "{}:{}: {:?}",
                    source.path, literal.line, literal.content
                ));
            }
        }
    }
    assert!(
        found.is_empty(),
        "{} model name(s) in src/ outside src/model/:\n{}",
        found.len(),
        found.into_iter().collect::<Vec<_>>().join("\n")
    );
}
