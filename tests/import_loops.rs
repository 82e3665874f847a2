//! No source file of a crate imports itself back: when file A uses file B, directly or through a
//! chain of files, B does not use A.
//!
//! A file uses another when it names an item defined there, in a `use` declaration or in a path
//! in its code (types, calls, patterns, macros' paths and bodies), by a path starting with
//! `crate::`, `super::`, `self::` or a name in scope. Paths are resolved through the module tree
//! (`mod x;` is `x.rs` or `x/mod.rs`, an inline `mod x { … }` stays in its file) and through
//! every `use`, re-exports and globs included, to the file that defines the item; a path
//! through a module's name (`use super::raster;`, then `raster::Viewport`) is followed the same
//! way. `mod x;` declarations and re-exports (`pub use`, `pub(crate) use`, …) are not uses by
//! themselves, a file's test code is, and a file's use of itself is no loop.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::path::{Path, PathBuf};

use syn::buffer::{Cursor, TokenBuffer};
use syn::visit::Visit;

use crate::common::root;

/// More loops than this in one crate are reported as a count.
const MAX_LOOPS: usize = 500;

#[test]
fn the_library_has_no_import_loop() {
    assert_no_loops(&[root().join("src/lib.rs")]);
}

#[test]
fn the_command_line_has_no_import_loop() {
    assert_no_loops(&[
        root().join("cli/src/lib.rs"),
        root().join("cli/src/main.rs"),
    ]);
}

/// Fails with every loop of the crates rooted at `crate_roots`, one a line.
fn assert_no_loops(crate_roots: &[PathBuf]) {
    let mut lines = Vec::new();
    for crate_root in crate_roots {
        lines.extend(import_loops(crate_root, root()));
    }
    assert!(
        lines.is_empty(),
        "{} import loop{} between source files:\n{}",
        lines.len(),
        if lines.len() == 1 { "" } else { "s" },
        lines.join("\n")
    );
}

/// The import loops of the crate whose root file is `crate_root`, one a line
/// (`a.rs → b.rs → a.rs`, each file by its path from `base`), sorted; each loop starts at its
/// first file in path order, and once.
fn import_loops(crate_root: &Path, base: &Path) -> Vec<String> {
    let krate = Crate::load(crate_root);
    let graph = krate.uses();
    let name = |file: usize| {
        let path = &krate.files[file];
        path.strip_prefix(base)
            .unwrap_or(path)
            .to_string_lossy()
            .replace('\\', "/")
    };
    let mut loops = cycles(&graph);
    let more = loops.len().saturating_sub(MAX_LOOPS);
    loops.truncate(MAX_LOOPS);
    let mut lines: Vec<String> = loops
        .iter()
        .map(|cycle| {
            let mut names: Vec<String> = cycle.iter().map(|&f| name(f)).collect();
            names.push(name(cycle[0]));
            names.join(" → ")
        })
        .collect();
    lines.sort();
    if more > 0 {
        lines.push(format!("… and {more} more loops"));
    }
    lines
}

/// Every elementary cycle of `graph` (file → files it uses), each starting at its smallest
/// file, stopping a little past [`MAX_LOOPS`].
fn cycles(graph: &BTreeMap<usize, BTreeSet<usize>>) -> Vec<Vec<usize>> {
    let component = strong_components(graph);
    let mut found = Vec::new();
    for &start in graph.keys() {
        let mut path = vec![start];
        cycles_from(graph, &component, start, start, &mut path, &mut found);
    }
    found
}

/// The cycles through `start` that continue `path` (ending at `at`) over files after `start`
/// in `start`'s strong component.
fn cycles_from(
    graph: &BTreeMap<usize, BTreeSet<usize>>,
    component: &HashMap<usize, usize>,
    start: usize,
    at: usize,
    path: &mut Vec<usize>,
    found: &mut Vec<Vec<usize>>,
) {
    let Some(next) = graph.get(&at) else {
        return;
    };
    for &next in next {
        if found.len() > MAX_LOOPS {
            return;
        }
        if next == start {
            found.push(path.clone());
        } else if next > start
            && component.get(&next) == component.get(&start)
            && !path.contains(&next)
        {
            path.push(next);
            cycles_from(graph, component, start, next, path, found);
            path.pop();
        }
    }
}

/// The strong component of each file of `graph` (Tarjan's algorithm), by an arbitrary number.
fn strong_components(graph: &BTreeMap<usize, BTreeSet<usize>>) -> HashMap<usize, usize> {
    struct Tarjan<'a> {
        graph: &'a BTreeMap<usize, BTreeSet<usize>>,
        index: HashMap<usize, usize>,
        low: HashMap<usize, usize>,
        stack: Vec<usize>,
        on_stack: HashSet<usize>,
        component: HashMap<usize, usize>,
    }
    impl Tarjan<'_> {
        fn visit(&mut self, v: usize) {
            let i = self.index.len();
            self.index.insert(v, i);
            self.low.insert(v, i);
            self.stack.push(v);
            self.on_stack.insert(v);
            for &w in self.graph.get(&v).into_iter().flatten() {
                if !self.index.contains_key(&w) {
                    self.visit(w);
                    let low = self.low[&v].min(self.low[&w]);
                    self.low.insert(v, low);
                } else if self.on_stack.contains(&w) {
                    let low = self.low[&v].min(self.index[&w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[&v] == self.index[&v] {
                let id = self.component.len();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(&w);
                    self.component.insert(w, id);
                    if w == v {
                        break;
                    }
                }
            }
        }
    }
    let mut tarjan = Tarjan {
        graph,
        index: HashMap::new(),
        low: HashMap::new(),
        stack: Vec::new(),
        on_stack: HashSet::new(),
        component: HashMap::new(),
    };
    for &v in graph.keys() {
        if !tarjan.index.contains_key(&v) {
            tarjan.visit(v);
        }
    }
    tarjan.component
}

/// A crate's source files, parsed, and its module tree.
struct Crate {
    files: Vec<PathBuf>,
    asts: Vec<syn::File>,
    modules: Vec<Module>,
}

/// One module: a file, or an inline `mod x { … }` within one.
struct Module {
    /// The file the module's items are written in.
    file: usize,
    parent: Option<usize>,
    children: HashMap<String, usize>,
    /// The names of the items defined in the module.
    items: HashSet<String>,
    /// The names brought in by `use`, with the path they name.
    imports: HashMap<String, Vec<String>>,
    /// The paths of the module's glob imports (`use x::*`).
    globs: Vec<Vec<String>>,
}

/// What a path names, as far as it matters here: a module, or an item defined in a file.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Target {
    Module(usize),
    File(usize),
}

/// One name or glob of a `use` tree, with the path it names.
struct UseLeaf {
    /// The name it brings in, `None` for a glob.
    name: Option<String>,
    path: Vec<String>,
}

impl Crate {
    /// Parses the crate whose root file is `root_file` and every file its modules declare.
    fn load(root_file: &Path) -> Self {
        let mut krate = Crate {
            files: Vec::new(),
            asts: Vec::new(),
            modules: Vec::new(),
        };
        let folder = root_file.parent().expect("a crate root lies in a folder");
        krate.add_file(root_file, folder, None);
        krate
    }

    /// Adds the module written in the file `path`, whose child modules' files are in `folder`.
    fn add_file(&mut self, path: &Path, folder: &Path, parent: Option<usize>) -> usize {
        let text = std::fs::read_to_string(path)
            .unwrap_or_else(|e| panic!("reading {}: {e}", path.display()));
        let ast =
            syn::parse_file(&text).unwrap_or_else(|e| panic!("parsing {}: {e}", path.display()));
        let file = self.files.len();
        self.files.push(path.to_path_buf());
        self.asts.push(ast.clone());
        self.add_module(file, &ast.items, folder, parent)
    }

    /// Adds the module with `items` written in `file`, whose child modules' files are in
    /// `folder`.
    fn add_module(
        &mut self,
        file: usize,
        items: &[syn::Item],
        folder: &Path,
        parent: Option<usize>,
    ) -> usize {
        let id = self.modules.len();
        self.modules.push(Module {
            file,
            parent,
            children: HashMap::new(),
            items: HashSet::new(),
            imports: HashMap::new(),
            globs: Vec::new(),
        });
        let mut block_uses = BlockUses::default();
        for item in items {
            let defined = match item {
                syn::Item::Const(i) => Some(&i.ident),
                syn::Item::Enum(i) => Some(&i.ident),
                syn::Item::Fn(i) => Some(&i.sig.ident),
                syn::Item::Macro(i) => i.ident.as_ref(),
                syn::Item::Static(i) => Some(&i.ident),
                syn::Item::Struct(i) => Some(&i.ident),
                syn::Item::Trait(i) => Some(&i.ident),
                syn::Item::TraitAlias(i) => Some(&i.ident),
                syn::Item::Type(i) => Some(&i.ident),
                syn::Item::Union(i) => Some(&i.ident),
                syn::Item::Mod(i) => {
                    let name = i.ident.to_string();
                    let child_folder = folder.join(&name);
                    let child = match &i.content {
                        Some((_, inner)) => self.add_module(file, inner, &child_folder, Some(id)),
                        None => {
                            let flat = folder.join(format!("{name}.rs"));
                            let path = if flat.exists() {
                                flat
                            } else {
                                child_folder.join("mod.rs")
                            };
                            self.add_file(&path, &child_folder, Some(id))
                        }
                    };
                    self.modules[id].children.insert(name, child);
                    None
                }
                syn::Item::Use(i) => {
                    self.add_use(id, &i.tree);
                    None
                }
                other => {
                    block_uses.visit_item(other);
                    None
                }
            };
            if let Some(ident) = defined {
                self.modules[id].items.insert(ident.to_string());
                block_uses.visit_item(item);
            }
        }
        // A `use` within a function is read as if it were the module's, unless the module
        // already has the name.
        for tree in &block_uses.trees {
            for leaf in use_leaves(tree) {
                let module = &mut self.modules[id];
                match leaf.name {
                    Some(name) => {
                        module.imports.entry(name).or_insert(leaf.path);
                    }
                    None => module.globs.push(leaf.path),
                }
            }
        }
        id
    }

    fn add_use(&mut self, module: usize, tree: &syn::UseTree) {
        for leaf in use_leaves(tree) {
            let module = &mut self.modules[module];
            match leaf.name {
                Some(name) => {
                    module.imports.insert(name, leaf.path);
                }
                None => module.globs.push(leaf.path),
            }
        }
    }

    fn root_module(&self) -> usize {
        0
    }

    /// What `name` means in `module`: a child module, an item defined there, or what an import
    /// names; explicit names before globs. `None` for a name from outside the crate or none.
    fn lookup(
        &self,
        module: usize,
        name: &str,
        seen: &mut HashSet<(usize, String)>,
    ) -> Option<Target> {
        if !seen.insert((module, name.to_string())) {
            return None;
        }
        let m = &self.modules[module];
        if let Some(&child) = m.children.get(name) {
            return Some(Target::Module(child));
        }
        if m.items.contains(name) {
            return Some(Target::File(m.file));
        }
        if let Some(path) = m.imports.get(name) {
            return self.resolve(module, path, seen);
        }
        m.globs
            .iter()
            .find_map(|glob| match self.resolve(module, glob, seen) {
                Some(Target::Module(source)) => self.lookup(source, name, seen),
                _ => None,
            })
    }

    /// What `path`, written in `module`, names. After a file's item the path's rest names
    /// something within it (a variant, an associated item); a name a module of the crate does
    /// not define (an item a macro writes) is taken to be in that module's file.
    fn resolve(
        &self,
        module: usize,
        path: &[String],
        seen: &mut HashSet<(usize, String)>,
    ) -> Option<Target> {
        let (first, rest) = path.split_first()?;
        let mut at = match first.as_str() {
            "crate" => Target::Module(self.root_module()),
            "self" => Target::Module(module),
            "super" => Target::Module(self.modules[module].parent?),
            _ => self.lookup(module, first, seen)?,
        };
        for segment in rest {
            let Target::Module(current) = at else {
                break;
            };
            at = match segment.as_str() {
                "self" => at,
                "super" => Target::Module(self.modules[current].parent?),
                _ => self
                    .lookup(current, segment, seen)
                    .unwrap_or(Target::File(self.modules[current].file)),
            };
        }
        Some(at)
    }

    /// Which files each file uses, itself left out.
    fn uses(&self) -> BTreeMap<usize, BTreeSet<usize>> {
        let mut graph = BTreeMap::new();
        let file_modules = self
            .modules
            .iter()
            .enumerate()
            .filter(|(_, m)| m.parent.is_none_or(|p| self.modules[p].file != m.file));
        for (id, module) in file_modules {
            let mut paths = Paths {
                krate: self,
                module: id,
                used: BTreeSet::new(),
            };
            paths.visit_file(&self.asts[module.file]);
            paths.used.remove(&module.file);
            graph.insert(module.file, paths.used);
        }
        graph
    }
}

/// The `use` trees within functions and other items of a module.
#[derive(Default)]
struct BlockUses {
    trees: Vec<syn::UseTree>,
}

impl Visit<'_> for BlockUses {
    fn visit_item_use(&mut self, i: &syn::ItemUse) {
        self.trees.push(i.tree.clone());
    }

    fn visit_item_mod(&mut self, _: &syn::ItemMod) {}
}

/// The names and globs of a `use` tree, each with its full path; nothing for a path from
/// outside every crate (`::x`).
fn use_leaves(tree: &syn::UseTree) -> Vec<UseLeaf> {
    fn walk(tree: &syn::UseTree, prefix: &mut Vec<String>, out: &mut Vec<UseLeaf>) {
        match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                walk(&p.tree, prefix, out);
                prefix.pop();
            }
            syn::UseTree::Name(n) if n.ident == "self" => out.push(UseLeaf {
                name: prefix.last().cloned(),
                path: prefix.clone(),
            }),
            syn::UseTree::Name(n) => {
                let mut path = prefix.clone();
                path.push(n.ident.to_string());
                out.push(UseLeaf {
                    name: Some(n.ident.to_string()),
                    path,
                });
            }
            syn::UseTree::Rename(r) => {
                let mut path = prefix.clone();
                if r.ident != "self" {
                    path.push(r.ident.to_string());
                }
                out.push(UseLeaf {
                    name: Some(r.rename.to_string()),
                    path,
                });
            }
            syn::UseTree::Glob(_) => out.push(UseLeaf {
                name: None,
                path: prefix.clone(),
            }),
            syn::UseTree::Group(g) => {
                for tree in &g.items {
                    walk(tree, prefix, out);
                }
            }
        }
    }
    let mut out = Vec::new();
    walk(tree, &mut Vec::new(), &mut out);
    out.retain(|leaf| !leaf.path.is_empty());
    out
}

/// Collects the files a module's code uses.
struct Paths<'a> {
    krate: &'a Crate,
    module: usize,
    used: BTreeSet<usize>,
}

impl Paths<'_> {
    fn note(&mut self, path: &[String]) {
        if let Some(Target::File(file)) = self.krate.resolve(self.module, path, &mut HashSet::new())
        {
            self.used.insert(file);
        }
    }
}

impl<'ast> Visit<'ast> for Paths<'_> {
    fn visit_item_mod(&mut self, i: &'ast syn::ItemMod) {
        // `mod x;` is no use; an inline module's code is the file's, read in its own scope.
        let Some((_, items)) = &i.content else {
            return;
        };
        let Some(&child) = self.krate.modules[self.module]
            .children
            .get(&i.ident.to_string())
        else {
            return;
        };
        let outer = std::mem::replace(&mut self.module, child);
        for item in items {
            self.visit_item(item);
        }
        self.module = outer;
    }

    fn visit_item_use(&mut self, i: &'ast syn::ItemUse) {
        // A re-export is no use by itself: what names the item through it is.
        if !matches!(i.vis, syn::Visibility::Inherited) || i.leading_colon.is_some() {
            return;
        }
        for leaf in use_leaves(&i.tree) {
            let target = self
                .krate
                .resolve(self.module, &leaf.path, &mut HashSet::new());
            // A module (or a glob of one) is followed where its names are used; a glob of an
            // enum's variants uses the enum's file.
            if let Some(Target::File(file)) = target {
                self.used.insert(file);
            }
        }
    }

    fn visit_attribute(&mut self, _: &'ast syn::Attribute) {}

    fn visit_path(&mut self, path: &'ast syn::Path) {
        if path.leading_colon.is_none() {
            let segments: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
            self.note(&segments);
        }
        syn::visit::visit_path(self, path);
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        self.visit_path(&mac.path);
        let buffer = TokenBuffer::new2(mac.tokens.clone());
        let mut paths = Vec::new();
        token_paths(buffer.begin(), &mut paths);
        for path in paths {
            self.note(&path);
        }
    }
}

/// The paths (`a`, `a::b::C`) written in a macro's tokens, except names after a `.` (fields
/// and methods) and paths from outside every crate (`::a`).
fn token_paths(mut cursor: Cursor, out: &mut Vec<Vec<String>>) {
    let mut current: Vec<String> = Vec::new();
    let mut after_colons = false;
    let mut after_dot = false;
    let mut outside = false;
    while !cursor.eof() {
        if let Some((ident, next)) = cursor.ident() {
            if after_colons && !current.is_empty() {
                current.push(ident.to_string());
            } else {
                if !current.is_empty() && !outside {
                    out.push(std::mem::take(&mut current));
                }
                current.clear();
                outside = after_colons;
                if !after_dot {
                    current.push(ident.to_string());
                }
            }
            after_colons = false;
            after_dot = false;
            cursor = next;
            continue;
        }
        let mut colons = false;
        let mut dot = false;
        if let Some((punct, next)) = cursor.punct() {
            match punct.as_char() {
                ':' => match next.punct() {
                    Some((second, after)) if second.as_char() == ':' => {
                        colons = true;
                        cursor = after;
                    }
                    _ => cursor = next,
                },
                '.' => {
                    dot = true;
                    cursor = next;
                }
                _ => cursor = next,
            }
        } else if let Some((inside, _, _, next)) = cursor.any_group() {
            token_paths(inside, out);
            cursor = next;
        } else if let Some((_, next)) = cursor.token_tree() {
            cursor = next;
        } else {
            break;
        }
        if !colons && !current.is_empty() && !outside {
            out.push(std::mem::take(&mut current));
        }
        if !colons {
            current.clear();
            outside = false;
        }
        after_colons = colons;
        after_dot = dot;
    }
    if !current.is_empty() && !outside {
        out.push(current);
    }
}

/// The checker itself, on small trees of files.
mod checker {
    use super::*;

    /// Writes `files` (path from the folder, text) into a new temporary folder.
    fn tree(files: &[(&str, &str)]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        for (path, text) in files {
            let path = dir.path().join(path);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, text).unwrap();
        }
        dir
    }

    fn loops_of(dir: &tempfile::TempDir) -> Vec<String> {
        import_loops(&dir.path().join("src/lib.rs"), dir.path())
    }

    #[test]
    fn a_file_used_back_by_a_test_in_a_macro_is_a_loop() {
        let dir = tree(&[
            ("src/lib.rs", "mod a;\nmod b;\n"),
            (
                "src/a.rs",
                "use crate::b::B;\npub struct A;\npub fn a() -> B { B }\n",
            ),
            (
                "src/b.rs",
                "pub struct B;\n\
                 #[cfg(test)]\n\
                 mod tests {\n    #[test]\n    fn t() {\n        \
                 assert!(matches!(crate::a::a(), super::B));\n    }\n}\n",
            ),
        ]);
        assert_eq!(loops_of(&dir), ["src/a.rs → src/b.rs → src/a.rs"]);
    }

    #[test]
    fn a_chain_through_a_re_export_is_a_loop() {
        let dir = tree(&[
            ("src/lib.rs", "pub mod shapes;\npub mod plain;\n"),
            (
                "src/shapes/mod.rs",
                "mod circle;\nmod square;\nmod triangle;\n\
                 pub use circle::Circle;\npub use square::Square;\npub use triangle::*;\n\
                 pub fn all() -> (Circle, Square, Triangle) { todo!() }\n",
            ),
            (
                "src/shapes/circle.rs",
                "use super::Square;\npub struct Circle(pub Square);\n",
            ),
            (
                "src/shapes/square.rs",
                "pub struct Square(pub Box<super::Triangle>);\n",
            ),
            (
                "src/shapes/triangle.rs",
                "use crate::shapes;\npub struct Triangle;\n\
                 impl Triangle {\n    pub fn around(&self) -> Option<shapes::Circle> { None }\n}\n",
            ),
            (
                "src/plain.rs",
                "pub fn all() { let _ = crate::shapes::all(); }\n",
            ),
        ]);
        assert_eq!(
            loops_of(&dir),
            ["src/shapes/circle.rs → src/shapes/square.rs → src/shapes/triangle.rs → src/shapes/circle.rs"]
        );
    }

    #[test]
    fn uses_one_way_and_paths_in_comments_and_strings_are_no_loop() {
        let dir = tree(&[
            ("src/lib.rs", "pub mod geom;\npub mod render;\n"),
            (
                "src/geom/mod.rs",
                "mod point;\nmod plane;\npub use plane::Plane;\npub use point::Point;\n",
            ),
            (
                "src/geom/point.rs",
                "// Drawn by crate::render::draw.\n\
                 /// See [`crate::render::draw`].\n\
                 pub struct Point;\n\
                 pub const NOTE: &str = r#\"crate::render::draw { \"#;\n",
            ),
            (
                "src/geom/plane.rs",
                "use super::point::Point;\npub struct Plane { pub at: Point }\n\
                 #[cfg(test)]\nmod tests {\n    use super::*;\n    \
                 #[test]\n    fn t() { let _ = Plane { at: Point }; \
                 let _ = \"crate::render::draw()\"; }\n}\n",
            ),
            (
                "src/render/mod.rs",
                "use crate::geom;\nuse crate::geom::{Plane, Point};\n\
                 pub fn draw(_: &Plane) -> geom::Point { Point }\n",
            ),
        ]);
        assert_eq!(loops_of(&dir), Vec::<String>::new());
    }
}
