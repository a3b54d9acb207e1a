//! The shape of the workspace, checked on its source text: the files of each crate's `src/`
//! import one another without a cycle, no source file grows past `MAX_CODE_LINES` lines of
//! code, and no file points readers at notes outside this repository.
//!
//! The import graph is built from the text, not from the compiler: every `crate::…` and
//! `super::…` path (in `use` trees, expanded, and in expressions and types) is resolved to the
//! file that defines the module it names, the longest prefix of the path that is a file
//! module (`a/mod.rs` is the module `a`, the folder; an item named after its module, like
//! `crate::report::Row`, resolves to the file of `crate::report`). Comments, string and char
//! literals and `#[cfg(test)]` modules (inline ones, and files declared under `#[cfg(test)]`)
//! are left out. Paths relative to the module itself (`pub use child::Item` or
//! `pub use self::child::Item` in a `mod.rs`) are not followed: they lead only down into the
//! file's own children, and are how a folder re-exports what its files define.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The most lines of code (non-blank, not comment) a source file may have outside its
/// `#[cfg(test)]` modules.
const MAX_CODE_LINES: usize = 800;

/// The crates whose `src/` the graph and the size limit cover, relative to the workspace.
const CRATE_SRCS: [&str; 2] = ["src", "crates/hexmesh-core/src"];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn files_under(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            files_under(&p, out);
        } else {
            out.push(p);
        }
    }
}

fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut all = Vec::new();
    files_under(dir, &mut all);
    all.retain(|p| p.extension().is_some_and(|e| e == "rs"));
    all
}

/// `text` with comments, string literals and char literals replaced by spaces (newlines
/// kept, so line numbers stay), leaving code only.
fn code_only(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |ch: char| if ch == '\n' { '\n' } else { ' ' };
    let mut i = 0;
    while i < c.len() {
        let next = c.get(i + 1).copied();
        if c[i] == '/' && next == Some('/') {
            while i < c.len() && c[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c[i] == '/' && next == Some('*') {
            // Block comments nest in Rust.
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && c.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(c[i]));
                    i += 1;
                }
            }
        } else if c[i] == 'r'
            && (next == Some('"') || next == Some('#'))
            && (i == 0 || !(c[i - 1].is_alphanumeric() || c[i - 1] == '_'))
        {
            // A raw string r"…" or r#"…"#, or an identifier that merely starts with r#.
            let mut j = i + 1;
            let mut hashes = 0;
            while c.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if c.get(j) != Some(&'"') {
                out.push(c[i]);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= c.len() {
                    break;
                }
                if c[j] == '"' && (1..=hashes).all(|k| c.get(j + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            for &ch in &c[i..j.min(c.len())] {
                out.push(blank(ch));
            }
            i = j;
        } else if c[i] == '"' {
            out.push(' ');
            i += 1;
            while i < c.len() && c[i] != '"' {
                if c[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < c.len() {
                    out.push(blank(c[i]));
                    i += 1;
                }
            }
            out.push(' ');
            i += 1;
        } else if c[i] == '\'' {
            // A char literal ('x', '\n', '\u{..}'), else a lifetime or label.
            let end = if next == Some('\\') {
                (i + 2..c.len().min(i + 12)).find(|&j| c[j] == '\'')
            } else if c.get(i + 2) == Some(&'\'') {
                Some(i + 2)
            } else {
                None
            };
            match end {
                Some(end) => {
                    for _ in i..=end {
                        out.push(' ');
                    }
                    i = end + 1;
                }
                None => {
                    out.push('\'');
                    i += 1;
                }
            }
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// The byte ranges of the `#[cfg(test)]` modules of `code` (comment-free): inline ones
/// with their braces, and `mod name;` declarations (whose names are returned too).
fn test_modules(code: &str) -> (Vec<(usize, usize)>, Vec<String>) {
    let mut ranges = Vec::new();
    let mut declared = Vec::new();
    let mut from = 0;
    while let Some(at) = code[from..].find("#[cfg(test)]") {
        let start = from + at;
        from = start + "#[cfg(test)]".len();
        let rest = &code[from..];
        let trimmed = rest.trim_start();
        // Further attributes may follow (#[allow(...)]), then an optional visibility.
        let mut s = trimmed;
        while s.starts_with("#[") {
            match s.find(']') {
                Some(e) => s = s[e + 1..].trim_start(),
                None => break,
            }
        }
        for vis in ["pub(crate)", "pub(super)", "pub"] {
            if let Some(r) = s.strip_prefix(vis) {
                s = r.trim_start();
                break;
            }
        }
        let Some(after_mod) = s.strip_prefix("mod ") else {
            continue;
        };
        let name: String = after_mod
            .trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let after_name = after_mod.trim_start()[name.len()..].trim_start();
        let pos = code.len() - after_name.len();
        if after_name.starts_with(';') {
            declared.push(name);
            ranges.push((start, pos + 1));
        } else if after_name.starts_with('{') {
            let mut depth = 0;
            let mut end = code.len();
            for (k, ch) in code[pos..].char_indices() {
                match ch {
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            end = pos + k + 1;
                            break;
                        }
                    }
                    _ => {}
                }
            }
            ranges.push((start, end));
            from = end;
        }
    }
    (ranges, declared)
}

/// `code` with its `#[cfg(test)]` modules blanked out (newlines kept), and the names of the
/// test-only modules it declares as files.
fn without_tests(code: &str) -> (String, Vec<String>) {
    let (ranges, declared) = test_modules(code);
    let mut out: Vec<u8> = code.as_bytes().to_vec();
    for (a, b) in ranges {
        for byte in &mut out[a..b] {
            if *byte != b'\n' {
                *byte = b' ';
            }
        }
    }
    (String::from_utf8_lossy(&out).into_owned(), declared)
}

/// The module path of a source file of a crate whose `src/` is `src`: `a/b.rs` and
/// `a/b/mod.rs` are `["a", "b"]`, `lib.rs` is `[]`. `None` for files of other crate roots
/// (`bin/`, `main.rs`).
fn module_of(src: &Path, file: &Path) -> Option<Vec<String>> {
    let rel = file.strip_prefix(src).ok()?;
    let mut parts: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    if parts.first().is_some_and(|p| p == "bin") || parts == ["main.rs"] {
        return None;
    }
    let last = parts.pop()?;
    match last.as_str() {
        "lib.rs" | "mod.rs" => {}
        other => parts.push(other.trim_end_matches(".rs").to_string()),
    }
    Some(parts)
}

fn is_ident(s: &str) -> bool {
    !s.is_empty()
        && s.chars().all(|c| c.is_alphanumeric() || c == '_')
        && !s.starts_with(|c: char| c.is_ascii_digit())
}

/// Every full path of a `use` tree (`a::{b, c::{d, e}}` gives `a::b`, `a::c::d`, `a::c::e`),
/// each as its segments; `self` inside braces names the prefix itself, `*` is dropped.
fn expand_use(tree: &str) -> Vec<Vec<String>> {
    fn split_top(s: &str) -> Vec<&str> {
        let (mut depth, mut start, mut out) = (0, 0, Vec::new());
        for (i, ch) in s.char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    out.push(&s[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        out.push(&s[start..]);
        out
    }
    fn walk(prefix: &[String], tree: &str, out: &mut Vec<Vec<String>>) {
        let tree = tree.trim();
        if tree.is_empty() {
            return;
        }
        // Drop a rename: `path as name`.
        let tree = match tree.find(" as ") {
            Some(i) if !tree[..i].contains('{') => &tree[..i],
            _ => tree,
        };
        let compact = |s: &str| s.split_whitespace().collect::<Vec<_>>().join("");
        if let Some(brace) = tree.find('{') {
            let head = compact(&tree[..brace]);
            let mut p = prefix.to_vec();
            p.extend(head.split("::").filter(|s| !s.is_empty()).map(String::from));
            let inner = &tree[brace + 1..tree.rfind('}').unwrap_or(tree.len())];
            for part in split_top(inner) {
                walk(&p, part, out);
            }
            return;
        }
        let mut p = prefix.to_vec();
        for seg in compact(tree).split("::") {
            match seg {
                "self" if !p.is_empty() => {}
                "*" => {}
                s => p.push(s.to_string()),
            }
        }
        out.push(p);
    }
    let mut out = Vec::new();
    walk(&[], tree, &mut out);
    out
}

/// The paths of `code` (comment-free, tests removed) that start at `crate`, `super` or
/// `self`, with the byte offset each starts at: the expanded `use` trees, and paths written
/// in expressions and types.
fn paths_in(code: &str) -> Vec<(usize, Vec<String>)> {
    let mut found = Vec::new();
    let bytes = code.as_bytes();
    let boundary =
        |i: usize| i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
    // `use` statements, whole trees.
    let mut use_spans = Vec::new();
    let mut from = 0;
    while let Some(at) = code[from..].find("use ") {
        let start = from + at;
        from = start + 4;
        if !boundary(start) {
            continue;
        }
        let Some(end) = code[start..].find(';').map(|e| start + e) else {
            break;
        };
        let tree = &code[start + 4..end];
        for path in expand_use(tree) {
            if path
                .first()
                .is_some_and(|s| s == "crate" || s == "super" || s == "self")
            {
                found.push((start, path));
            }
        }
        use_spans.push((start, end));
        from = end;
    }
    // Paths elsewhere: `crate::a::b`, `super::super::x`, `self::m::f`.
    for key in ["crate", "super", "self"] {
        let mut from = 0;
        while let Some(at) = code[from..].find(key) {
            let start = from + at;
            from = start + key.len();
            if !boundary(start) || use_spans.iter().any(|&(a, b)| a <= start && start < b) {
                continue;
            }
            let mut segs = vec![key.to_string()];
            let mut rest = &code[from..];
            loop {
                let r = rest.trim_start();
                let Some(r) = r.strip_prefix("::") else {
                    break;
                };
                let r = r.trim_start();
                let ident: String = r
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !is_ident(&ident) {
                    break;
                }
                rest = &r[ident.len()..];
                segs.push(ident);
            }
            if segs.len() > 1 {
                found.push((start, segs));
            }
        }
    }
    found
}

/// The starts of the inline (non-test) modules of `code`: `mod name {`, with the byte range
/// of their bodies, so that `self` and `super` inside them resolve from there.
fn inline_modules(code: &str) -> Vec<(String, usize, usize)> {
    let mut out = Vec::new();
    let bytes = code.as_bytes();
    let mut from = 0;
    while let Some(at) = code[from..].find("mod ") {
        let start = from + at;
        from = start + 4;
        if start > 0 && (bytes[start - 1].is_ascii_alphanumeric() || bytes[start - 1] == b'_') {
            continue;
        }
        let rest = code[from..].trim_start();
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let after = rest[name.len()..].trim_start();
        if !is_ident(&name) || !after.starts_with('{') {
            continue;
        }
        let open = code.len() - after.len();
        let mut depth = 0;
        let mut end = code.len();
        for (k, ch) in code[open..].char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + k;
                        break;
                    }
                }
                _ => {}
            }
        }
        out.push((name, open, end));
    }
    out
}

/// One source file of the graph.
struct SourceFile {
    /// Relative to the workspace, for messages.
    rel: String,
    /// Which crate (its `src/`).
    krate: &'static str,
    module: Vec<String>,
    /// Code without comments, literals and test modules.
    code: String,
}

/// An import: from file `from` to file `to`, by `path` on line `line` of `from`.
struct Edge {
    to: usize,
    path: String,
    line: usize,
}

fn load_sources() -> Vec<SourceFile> {
    let root = root();
    let mut files = Vec::new();
    for krate in CRATE_SRCS {
        let src = root.join(krate);
        let mut test_only: BTreeSet<Vec<String>> = BTreeSet::new();
        let mut these = Vec::new();
        for path in rust_files(&src) {
            let Some(module) = module_of(&src, &path) else {
                continue;
            };
            let text = std::fs::read_to_string(&path).expect("source file reads");
            let (code, declared) = without_tests(&code_only(&text));
            for name in declared {
                let mut m = module.clone();
                m.push(name);
                test_only.insert(m);
            }
            let rel = path
                .strip_prefix(&root)
                .unwrap_or(&path)
                .to_string_lossy()
                .into_owned();
            these.push(SourceFile {
                rel,
                krate,
                module,
                code,
            });
        }
        // Files declared only under #[cfg(test)], and whatever lies below them.
        these.retain(|f| !test_only.iter().any(|t| f.module.starts_with(t)));
        files.extend(these);
    }
    files
}

/// Every import edge of every file (self-imports dropped), by file index.
fn import_graph(files: &[SourceFile]) -> Vec<Vec<Edge>> {
    let mut by_module: BTreeMap<(&str, &[String]), usize> = BTreeMap::new();
    for (i, f) in files.iter().enumerate() {
        by_module.insert((f.krate, f.module.as_slice()), i);
    }
    files
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let inline = inline_modules(&f.code);
            let mut edges: Vec<Edge> = Vec::new();
            for (at, path) in paths_in(&f.code) {
                if path[0] == "self" {
                    continue;
                }
                // The module the path is written in: the file's, plus the inline modules
                // around it.
                let mut here = f.module.clone();
                for (name, open, end) in &inline {
                    if *open < at && at < *end {
                        here.push(name.clone());
                    }
                }
                let mut abs: Vec<String> = Vec::new();
                let mut segs = path.iter().peekable();
                match segs.peek().map(|s| s.as_str()) {
                    Some("crate") => {
                        segs.next();
                    }
                    _ => {
                        abs = here.clone();
                        while segs.peek().is_some_and(|s| *s == "super") {
                            segs.next();
                            abs.pop();
                        }
                    }
                }
                abs.extend(segs.cloned());
                // The longest prefix that is a file module.
                let to = (0..=abs.len())
                    .rev()
                    .find_map(|n| by_module.get(&(f.krate, &abs[..n])).copied());
                if let Some(to) = to.filter(|&to| to != i) {
                    if !edges.iter().any(|e| e.to == to) {
                        let line = f.code[..at].matches('\n').count() + 1;
                        edges.push(Edge {
                            to,
                            path: path.join("::"),
                            line,
                        });
                    }
                }
            }
            edges
        })
        .collect()
}

/// The strongly connected components of more than one file (Tarjan), each as a cycle
/// through its files, by file index.
fn cycles(graph: &[Vec<Edge>]) -> Vec<Vec<usize>> {
    struct Tarjan<'a> {
        graph: &'a [Vec<Edge>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        sccs: Vec<Vec<usize>>,
    }
    impl Tarjan<'_> {
        fn visit(&mut self, v: usize) {
            self.index[v] = Some(self.next);
            self.low[v] = self.next;
            self.next += 1;
            self.stack.push(v);
            self.on_stack[v] = true;
            for e in &self.graph[v] {
                match self.index[e.to] {
                    None => {
                        self.visit(e.to);
                        self.low[v] = self.low[v].min(self.low[e.to]);
                    }
                    Some(w) if self.on_stack[e.to] => self.low[v] = self.low[v].min(w),
                    Some(_) => {}
                }
            }
            if Some(self.low[v]) == self.index[v] {
                let mut scc = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack[w] = false;
                    scc.push(w);
                    if w == v {
                        break;
                    }
                }
                if scc.len() > 1 {
                    self.sccs.push(scc);
                }
            }
        }
    }
    let n = graph.len();
    let mut t = Tarjan {
        graph,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        sccs: Vec::new(),
    };
    for v in 0..n {
        if t.index[v].is_none() {
            t.visit(v);
        }
    }
    // One cycle through each component: a shortest path back to its smallest file.
    t.sccs
        .iter()
        .map(|scc| {
            let start = *scc.iter().min().expect("non-empty");
            let inside: BTreeSet<usize> = scc.iter().copied().collect();
            let mut prev: BTreeMap<usize, usize> = BTreeMap::new();
            let mut queue = std::collections::VecDeque::from([start]);
            let mut last = None;
            'bfs: while let Some(v) = queue.pop_front() {
                for e in &graph[v] {
                    if e.to == start {
                        last = Some(v);
                        break 'bfs;
                    }
                    if inside.contains(&e.to) && !prev.contains_key(&e.to) {
                        prev.insert(e.to, v);
                        queue.push_back(e.to);
                    }
                }
            }
            let mut cycle = vec![last.expect("a component has a cycle")];
            while let Some(&p) = prev.get(cycle.last().expect("non-empty")) {
                cycle.push(p);
            }
            if cycle.last() != Some(&start) {
                cycle.push(start);
            }
            cycle.reverse();
            cycle
        })
        .collect()
}

#[test]
fn no_file_imports_a_file_that_imports_it_back() {
    let files = load_sources();
    assert!(files.len() > 50, "found only {} source files", files.len());
    let graph = import_graph(&files);
    let found = cycles(&graph);
    let shown: Vec<String> = found
        .iter()
        .map(|cycle| {
            let mut s = files[cycle[0]].rel.clone();
            for (k, &v) in cycle.iter().enumerate() {
                let w = cycle[(k + 1) % cycle.len()];
                let e = graph[v]
                    .iter()
                    .find(|e| e.to == w)
                    .expect("an edge of the cycle");
                s.push_str(&format!(
                    "\n    -> {} (`{}` at line {})",
                    files[w].rel, e.path, e.line
                ));
            }
            s
        })
        .collect();
    assert!(
        found.is_empty(),
        "{} import cycle(s) between files:\n  {}",
        found.len(),
        shown.join("\n  ")
    );
}

/// Lines of `code` (comment-free) that hold code.
fn code_lines(code: &str) -> usize {
    code.lines().filter(|l| !l.trim().is_empty()).count()
}

#[test]
fn no_source_file_has_more_than_800_lines_of_code_outside_its_tests() {
    let root = root();
    let mut over = Vec::new();
    for krate in CRATE_SRCS {
        for path in rust_files(&root.join(krate)) {
            let text = std::fs::read_to_string(&path).expect("source file reads");
            let (code, _) = without_tests(&code_only(&text));
            let n = code_lines(&code);
            if n > MAX_CODE_LINES {
                over.push(format!(
                    "{}: {n} lines of code",
                    path.strip_prefix(&root).unwrap_or(&path).display()
                ));
            }
        }
    }
    assert!(
        over.is_empty(),
        "files with more than {MAX_CODE_LINES} lines of code (not blank, not comment, outside \
         #[cfg(test)] modules):\n  {}",
        over.join("\n  ")
    );
}

#[test]
fn no_file_points_at_notes_outside_the_repository() {
    // Spelled in pieces, so this file does not name them itself.
    let needles = [
        ["DESIGN", ".md"].concat(),
        ["shared", "/papers"].concat(),
        ["..", "/shared"].concat(),
    ];
    let root = root();
    let mut files = Vec::new();
    for dir in ["src", "crates", "tests", "benches", "examples", "docs"] {
        files_under(&root.join(dir), &mut files);
    }
    files.push(root.join("README.md"));
    let mut hits = Vec::new();
    for path in files {
        let Ok(bytes) = std::fs::read(&path) else {
            continue;
        };
        let text = String::from_utf8_lossy(&bytes);
        for (n, line) in text.lines().enumerate() {
            for needle in &needles {
                if line.contains(needle.as_str()) {
                    hits.push(format!(
                        "{}:{}: {needle}",
                        path.strip_prefix(&root).unwrap_or(&path).display(),
                        n + 1
                    ));
                }
            }
        }
    }
    assert!(
        hits.is_empty(),
        "{} mention(s) of notes outside the repository:\n  {}",
        hits.len(),
        hits.join("\n  ")
    );
}

#[test]
fn the_reader_finds_paths_in_use_trees_and_code_but_not_in_comments_strings_or_tests() {
    let text = r##"
use crate::a::{b::{self, C}, d as e};
use super::super::f::G;
// crate::commented::out
/* crate::block /* nested */ crate::still_comment */
fn h() { let s = "crate::in_string"; let r = r#"crate::raw"#; let c = '"'; crate::x::y(); }
fn lt<'a>(v: &'a str) -> &'a str { self::z::w(v) }
#[cfg(test)]
mod tests { use crate::only_in_tests; }
"##;
    let (code, _) = without_tests(&code_only(text));
    let mut paths: Vec<String> = paths_in(&code)
        .into_iter()
        .map(|(_, p)| p.join("::"))
        .collect();
    paths.sort();
    assert_eq!(
        paths,
        [
            "crate::a::b",
            "crate::a::b::C",
            "crate::a::d",
            "crate::x::y",
            "self::z::w",
            "super::super::f::G"
        ]
    );
    let (_, declared) = without_tests(&code_only("#[cfg(test)]\nmod fixtures;\nmod real;\n"));
    assert_eq!(declared, ["fixtures"]);
}

#[test]
fn cycles_are_found_and_shown_through_their_files() {
    let edge = |to| Edge {
        to,
        path: String::new(),
        line: 0,
    };
    // 0 -> 1 -> 2 -> 0, and 3 -> 0 outside the cycle.
    let graph = vec![vec![edge(1)], vec![edge(2)], vec![edge(0)], vec![edge(0)]];
    assert_eq!(cycles(&graph), [vec![0, 1, 2]]);
    let acyclic = vec![vec![edge(1)], vec![edge(2)], vec![], vec![edge(0)]];
    assert!(cycles(&acyclic).is_empty());
}
