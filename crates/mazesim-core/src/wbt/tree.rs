//! The node tree of a `.wbt` file: nodes with fields, `DEF` / `USE` sharing, `EXTERNPROTO`
//! declarations. Field arity is not written in the file, so a field keeps every number, string,
//! boolean and node that follows its name; the importer decides what it expects.

use super::header::WbtVersion;

/// Index of a node in [`Document::nodes`].
pub type NodeId = usize;

/// The values that follow a field name.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Value {
    /// Numbers in order.
    pub numbers: Vec<f64>,
    /// Strings in order.
    pub strings: Vec<String>,
    /// `TRUE` / `FALSE` in order.
    pub bools: Vec<bool>,
    /// Nodes in order (`NULL` and unresolved `USE` leave no entry).
    pub nodes: Vec<NodeId>,
}

/// A field of a node.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Its name.
    pub name: String,
    /// What follows the name.
    pub value: Value,
    /// Line of the name.
    pub line: usize,
    /// Column of the name.
    pub column: usize,
}

/// A node: `Type { field value ... }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// Its type: a base node (`Solid`, `Box`) or a PROTO (`E-puck`, `WoodenBox`).
    pub type_name: String,
    /// The `DEF` name given to it, if any.
    pub def_name: Option<String>,
    /// Fields in file order.
    pub fields: Vec<Field>,
    /// Line of the type name.
    pub line: usize,
    /// Column of the type name.
    pub column: usize,
}

impl Node {
    /// The field of that name (the last one if written twice).
    pub fn field(&self, name: &str) -> Option<&Field> {
        self.fields.iter().rev().find(|f| f.name == name)
    }
}

/// A parsed world file.
#[derive(Debug, Clone, PartialEq)]
pub struct Document {
    /// The Webots version of the header.
    pub version: WbtVersion,
    /// URLs of the `EXTERNPROTO` declarations.
    pub externprotos: Vec<String>,
    /// Every node; `USE` refers to an existing entry, so the tree is a DAG.
    pub nodes: Vec<Node>,
    /// The top-level nodes in file order.
    pub roots: Vec<NodeId>,
    /// Things read but not understood (an unknown `USE`, an inline PROTO definition, a ROUTE).
    pub warnings: Vec<String>,
}

impl Document {
    /// The node of an id.
    pub fn node(&self, id: NodeId) -> &Node {
        &self.nodes[id]
    }

    /// Whether an `EXTERNPROTO` declares a PROTO of that type name (its file stem).
    pub fn declares_proto(&self, type_name: &str) -> bool {
        self.externprotos.iter().any(|url| {
            let file = url.rsplit('/').next().unwrap_or(url);
            file.strip_suffix(".proto") == Some(type_name)
        })
    }
}
