//! The reader of a `.wbt` text: header, `EXTERNPROTO` lines, then nodes; `DEF` names are
//! registered once their node is complete, so `USE` finds the most recent earlier DEF; `hidden`
//! lines are skipped; inline PROTO definitions and ROUTEs are skipped with a warning.

use std::collections::HashMap;

use super::header::parse_header;
use super::lexer::{tokenize, Token, TokenKind};
use super::tree::{Document, Field, Node, NodeId, Value};
use crate::error::{Error, Result};
use crate::file_kind::{named_for_its_kind, FileKind};

/// Most nodes a world may stand for once every `USE` is expanded: far above any real world (the
/// largest test world has a few thousand), far below what exhausts memory.
pub const MAX_EXPANDED_NODES: u64 = 1 << 20;

/// Deepest nesting of nodes and brackets the reader accepts (real worlds stay under 30).
pub const MAX_DEPTH: usize = 100;

/// Refuses, before a token is made, a text of more node bodies (`{`, outside strings and
/// comments) than a world may hold nodes: the reader's tokens and tree of such a text take
/// gigabytes (600,000 Solids in 83 MB took 2 GB) before the node count refuses them, and an
/// allocation the system refuses aborts the process. A byte scan, allocating nothing.
fn check_node_bodies(text: &str, source: &str) -> Result<()> {
    let bytes = text.as_bytes();
    let (mut bodies, mut line, mut i) = (0u64, 1usize, 0usize);
    while i < bytes.len() {
        match bytes[i] {
            b'\n' => line += 1,
            b'#' => {
                while i + 1 < bytes.len() && bytes[i + 1] != b'\n' {
                    i += 1;
                }
            }
            b'"' => {
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' {
                    if bytes[i] == b'\\' {
                        i += 1;
                    } else if bytes[i] == b'\n' {
                        line += 1;
                    }
                    i += 1;
                }
            }
            b'{' => {
                bodies += 1;
                if bodies > MAX_EXPANDED_NODES {
                    return Err(Error::format_at(
                        source,
                        line,
                        1,
                        "(top level)",
                        format!(
                            "expected a world of at most {MAX_EXPANDED_NODES} nodes, found more \
                             node bodies than that by line {line}"
                        ),
                    ));
                }
            }
            _ => {}
        }
        i += 1;
    }
    Ok(())
}

impl Document {
    /// Parses a world file's text; `source` names it in error messages.
    pub fn parse(text: &str, source: &str) -> Result<Document> {
        let (version, warnings) = parse_header(text, source)?;
        check_node_bodies(text, source)?;
        let tokens = tokenize(text, source)?;
        let mut parser = Parser {
            source,
            end: end_position(text),
            tokens,
            pos: 0,
            nodes: Vec::new(),
            expanded: Vec::new(),
            expanded_roots: 0,
            defs: HashMap::new(),
            warnings,
            path: Vec::new(),
            depth: 0,
        };
        let mut externprotos = Vec::new();
        let mut roots = Vec::new();
        while let Some(token) = parser.peek().cloned() {
            match &token.kind {
                TokenKind::Word(w) if w == "EXTERNPROTO" || w == "IMPORTABLE" => {
                    parser.pos += 1;
                    if w == "IMPORTABLE" {
                        parser.expect_keyword("EXTERNPROTO")?;
                    }
                    externprotos.push(parser.expect_string("the URL of an EXTERNPROTO")?);
                }
                TokenKind::Word(w) if w == "PROTO" => parser.skip_proto_definition(&token)?,
                TokenKind::Word(w) if w == "ROUTE" => {
                    parser.warn(&token, "ROUTE statements are not used by mazesim; skipped");
                    parser.skip_line(token.line);
                }
                _ => {
                    if let Some(id) = parser.node_statement("the top level")? {
                        parser.add_root(id)?;
                        roots.push(id);
                    }
                }
            }
        }
        if roots.is_empty() && FileKind::sniff(text) == Some(FileKind::WebotsProto) {
            // A PROTO file holds a node's definition and no world: imported, it would be an
            // empty world without a word.
            let empty = Error::format_at(source, 1, 1, "(top level)", "expected a world");
            return Err(named_for_its_kind(
                text,
                source,
                FileKind::WebotsWorld,
                empty,
            ));
        }
        Ok(Document {
            version,
            externprotos,
            nodes: parser.nodes,
            roots,
            warnings: parser.warnings,
        })
    }
}

fn end_position(text: &str) -> (usize, usize) {
    let line = text.matches('\n').count() + 1;
    let last = text.rsplit('\n').next().unwrap_or("");
    (line, last.chars().count() + 1)
}

fn describe(token: Option<&Token>) -> String {
    match token.map(|t| &t.kind) {
        None => "the end of the file".into(),
        Some(TokenKind::OpenBrace) => "`{`".into(),
        Some(TokenKind::CloseBrace) => "`}`".into(),
        Some(TokenKind::OpenBracket) => "`[`".into(),
        Some(TokenKind::CloseBracket) => "`]`".into(),
        Some(TokenKind::Number(n)) => format!("the number {n}"),
        Some(TokenKind::Str(s)) => {
            format!("the string {:?}", s.chars().take(30).collect::<String>())
        }
        Some(TokenKind::Word(w) | TokenKind::NotANumber(w)) => {
            format!("`{}`", w.chars().take(30).collect::<String>())
        }
    }
}

/// Whether a word spells a number that is not finite (`nan`, `-inf`, `Infinity`): no field is
/// named so, and where a number stands it is a bad one, not the next field's name.
fn spells_non_finite(word: &str) -> bool {
    let unsigned = word
        .strip_prefix(['-', '+'])
        .unwrap_or(word)
        .to_ascii_lowercase();
    matches!(unsigned.as_str(), "nan" | "inf" | "infinity")
}

struct Parser<'a> {
    source: &'a str,
    end: (usize, usize),
    tokens: Vec<Token>,
    pos: usize,
    nodes: Vec<Node>,
    /// Per node: how many nodes it stands for once every `USE` under it is expanded.
    expanded: Vec<u64>,
    /// The same, summed over the top-level nodes read so far.
    expanded_roots: u64,
    defs: HashMap<String, NodeId>,
    warnings: Vec<String>,
    /// Node types and field names from the top down to where the parser is, for error messages.
    path: Vec<String>,
    depth: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.pos)
    }

    fn peek_word(&self) -> Option<&str> {
        match self.peek().map(|t| &t.kind) {
            Some(TokenKind::Word(w)) => Some(w),
            _ => None,
        }
    }

    fn error_here(&self, message: String) -> Error {
        let (line, column) = self.peek().map_or(self.end, |t| (t.line, t.column));
        let field = if self.path.is_empty() {
            "(top level)".to_string()
        } else {
            self.path.join(".")
        };
        Error::format_at(self.source, line, column, &field, message)
    }

    fn warn(&mut self, at: &Token, message: &str) {
        self.warnings.push(format!("line {}: {message}", at.line));
    }

    fn skip_line(&mut self, line: usize) {
        while self.peek().is_some_and(|t| t.line == line) {
            self.pos += 1;
        }
    }

    fn expect_keyword(&mut self, keyword: &str) -> Result<()> {
        if self.peek_word() == Some(keyword) {
            self.pos += 1;
            Ok(())
        } else {
            Err(self.error_here(format!(
                "expected `{keyword}`, found {}",
                describe(self.peek())
            )))
        }
    }

    fn expect_string(&mut self, what: &str) -> Result<String> {
        match self.peek().map(|t| t.kind.clone()) {
            Some(TokenKind::Str(s)) => {
                self.pos += 1;
                Ok(s)
            }
            _ => Err(self.error_here(format!(
                "expected {what} (a string), found {}",
                describe(self.peek())
            ))),
        }
    }

    fn expect_name(&mut self, what: &str) -> Result<String> {
        match self.peek_word() {
            Some(w) if !matches!(w, "DEF" | "USE" | "NULL" | "TRUE" | "FALSE") => {
                let w = w.to_string();
                self.pos += 1;
                Ok(w)
            }
            _ => Err(self.error_here(format!("expected {what}, found {}", describe(self.peek())))),
        }
    }

    fn enter(&mut self) -> Result<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.error_here(format!(
                "expected at most {MAX_DEPTH} levels of nested nodes and lists, found more"
            )));
        }
        Ok(())
    }

    /// Skips `PROTO Name [ interface ] { body }` written inside a world file.
    fn skip_proto_definition(&mut self, at: &Token) -> Result<()> {
        self.pos += 1;
        let name = self.expect_name("the name of the PROTO")?;
        self.warn(at, &format!("the PROTO definition `{name}` inside the world is not expanded; its instances are reported as unknown"));
        for (open, close) in [
            (TokenKind::OpenBracket, TokenKind::CloseBracket),
            (TokenKind::OpenBrace, TokenKind::CloseBrace),
        ] {
            if self.peek().map(|t| &t.kind) != Some(&open) {
                return Err(self.error_here(format!(
                    "expected {} in the PROTO definition `{name}`, found {}",
                    describe(Some(&Token {
                        kind: open,
                        line: 0,
                        column: 0
                    })),
                    describe(self.peek())
                )));
            }
            let mut level = 0usize;
            while let Some(t) = self.peek() {
                if t.kind == open {
                    level += 1;
                } else if t.kind == close {
                    level -= 1;
                }
                self.pos += 1;
                if level == 0 {
                    break;
                }
            }
            if level != 0 {
                return Err(self.error_here(format!(
                    "expected the end of the PROTO definition `{name}`, found the end of the file"
                )));
            }
        }
        Ok(())
    }

    /// `DEF name Node`, `USE name`, `NULL` or `Type { ... }`; `None` for NULL or an unknown USE.
    fn node_statement(&mut self, place: &str) -> Result<Option<NodeId>> {
        let Some(token) = self.peek().cloned() else {
            return Err(self.error_here(format!(
                "expected a node in {place}, found the end of the file"
            )));
        };
        match &token.kind {
            TokenKind::Word(w) if w == "NULL" => {
                self.pos += 1;
                Ok(None)
            }
            TokenKind::Word(w) if w == "USE" => {
                self.pos += 1;
                let name = self.expect_name("the DEF name after USE")?;
                match self.defs.get(&name) {
                    Some(&id) => Ok(Some(id)),
                    None => {
                        self.warn(
                            &token,
                            &format!("USE {name}: no earlier DEF {name}; ignored"),
                        );
                        Ok(None)
                    }
                }
            }
            TokenKind::Word(w) if w == "DEF" => {
                self.pos += 1;
                let name = self.expect_name("the name after DEF")?;
                let id = self.node_body()?;
                self.nodes[id].def_name = Some(name.clone());
                // Registered once complete: a USE refers to the most recent earlier DEF.
                self.defs.insert(name, id);
                Ok(Some(id))
            }
            TokenKind::Word(_) => self.node_body().map(Some),
            _ => Err(self.error_here(format!(
                "expected a node in {place}, found {}",
                describe(Some(&token))
            ))),
        }
    }

    /// `Type { fields }`.
    fn node_body(&mut self) -> Result<NodeId> {
        let token = self.peek().cloned();
        let type_name = self.expect_name("a node type")?;
        let token = token.expect("a name was read, so there was a token");
        if self.peek().map(|t| &t.kind) != Some(&TokenKind::OpenBrace) {
            return Err(self.error_here(format!(
                "expected `{{` after the node type `{type_name}`, found {}",
                describe(self.peek())
            )));
        }
        self.pos += 1;
        self.enter()?;
        self.path.push(type_name.clone());
        let mut fields = Vec::new();
        loop {
            let Some(t) = self.peek().cloned() else {
                return Err(self.error_here(format!(
                    "expected `}}` to close `{type_name}` opened on line {}, found the end of the file",
                    token.line
                )));
            };
            match &t.kind {
                TokenKind::CloseBrace => {
                    self.pos += 1;
                    break;
                }
                TokenKind::Word(w) if w == "hidden" => self.skip_line(t.line),
                TokenKind::Word(name) => {
                    self.pos += 1;
                    self.path.push(name.clone());
                    let value = self.field_value(name)?;
                    self.path.pop();
                    fields.push(Field {
                        name: name.clone(),
                        value,
                        line: t.line,
                        column: t.column,
                    });
                }
                _ => {
                    return Err(self.error_here(format!(
                        "expected a field name or `}}` in `{type_name}`, found {}",
                        describe(Some(&t))
                    )))
                }
            }
        }
        self.path.pop();
        self.depth -= 1;
        let children = fields.iter().flat_map(|f| &f.value.nodes);
        let expanded = children.fold(1u64, |n, &c| n.saturating_add(self.expanded[c]));
        self.check_expansion((token.line, token.column), &type_name, expanded)?;
        self.expanded.push(expanded);
        self.nodes.push(Node {
            type_name,
            def_name: None,
            fields,
            line: token.line,
            column: token.column,
        });
        Ok(self.nodes.len() - 1)
    }

    /// Refuses a node that stands for more than `MAX_EXPANDED_NODES` nodes once its `USE`s are
    /// expanded (a few lines of nested `DEF` / `USE` double at every level), before anything walks
    /// the expansion.
    fn check_expansion(&self, at: (usize, usize), type_name: &str, expanded: u64) -> Result<()> {
        if expanded <= MAX_EXPANDED_NODES {
            return Ok(());
        }
        let field = if self.path.is_empty() {
            "(top level)".to_string()
        } else {
            self.path.join(".")
        };
        Err(Error::format_at(
            self.source,
            at.0,
            at.1,
            &field,
            format!(
                "expected a world of at most {MAX_EXPANDED_NODES} nodes once every USE is \
                 expanded, found `{type_name}` standing for {expanded}"
            ),
        ))
    }

    /// Counts a top-level node's expansion towards the document's (see `check_expansion`).
    fn add_root(&mut self, id: NodeId) -> Result<()> {
        self.expanded_roots = self.expanded_roots.saturating_add(self.expanded[id]);
        let node = &self.nodes[id];
        self.check_expansion(
            (node.line, node.column),
            &node.type_name,
            self.expanded_roots,
        )
    }

    fn is_node_start(&self) -> bool {
        match self.peek_word() {
            Some("DEF" | "USE" | "NULL") => true,
            Some(_) => {
                self.tokens.get(self.pos + 1).map(|t| &t.kind) == Some(&TokenKind::OpenBrace)
            }
            None => false,
        }
    }

    /// Whether the token at `at` can start a field's value (what follows a field name).
    fn starts_value(&self, at: usize) -> bool {
        match self.tokens.get(at).map(|t| &t.kind) {
            Some(TokenKind::Number(_) | TokenKind::Str(_) | TokenKind::OpenBracket) => true,
            Some(TokenKind::Word(w)) => {
                matches!(w.as_str(), "TRUE" | "FALSE" | "IS" | "DEF" | "USE" | "NULL")
                    || self.tokens.get(at + 1).map(|t| &t.kind) == Some(&TokenKind::OpenBrace)
            }
            _ => false,
        }
    }

    /// The next token's text when it stands among the numbers of `value` and is no finite number:
    /// text that starts as a number does (`1e400`), a word spelling one that is not finite
    /// (`nan`), or, after a number, a word that no value follows (so no field name either).
    fn not_a_number(&self, value: &Value) -> Option<String> {
        match self.peek().map(|t| &t.kind) {
            Some(TokenKind::NotANumber(w)) => Some(w.clone()),
            Some(TokenKind::Word(w)) if spells_non_finite(w) => Some(w.clone()),
            Some(TokenKind::Word(w))
                if !value.numbers.is_empty()
                    && w != "hidden"
                    && !self.is_node_start()
                    && !self.starts_value(self.pos + 1) =>
            {
                Some(w.clone())
            }
            _ => None,
        }
    }

    /// The error of a token among the numbers of the field `name` that is no finite number: the
    /// same for every numeric field, at the token's line.
    fn refuse_number(&self, name: &str, value: &Value, found: &str) -> Error {
        let read = value.numbers.len();
        let after = match read {
            0 => String::new(),
            1 => " after its first number".to_string(),
            n => format!(" after its first {n} numbers"),
        };
        self.error_here(format!(
            "expected the field `{name}` to hold finite numbers, found `{found}`{after}"
        ))
    }

    /// Refuses a vector field of a Webots base node (see [`vector_length`]) given fewer numbers
    /// than it holds, as Webots does: it reads the next word as the missing number and stops
    /// loading the world. More numbers than it holds are left to the import's warning.
    fn check_vector_length(&self, name: &str, value: &Value) -> Result<()> {
        let node = self
            .path
            .len()
            .checked_sub(2)
            .map(|i| self.path[i].as_str());
        let Some(length) = node.and_then(|node| vector_length(node, name)) else {
            return Ok(());
        };
        let read = value.numbers.len();
        if read == 0 || read >= length || !value.strings.is_empty() || !value.bools.is_empty() {
            return Ok(());
        }
        Err(self.error_here(format!(
            "expected the field `{name}` to hold {length} numbers, found {read}, then {} \
             (Webots refuses the world too)",
            describe(self.peek())
        )))
    }

    /// Adds one scalar (number, string, boolean) to `value`; false when the next token is none.
    fn scalar(&mut self, value: &mut Value) -> bool {
        let kind = match self.peek() {
            Some(t) => t.kind.clone(),
            None => return false,
        };
        match kind {
            TokenKind::Number(n) => value.numbers.push(n),
            TokenKind::Str(s) => value.strings.push(s),
            TokenKind::Word(w) if w == "TRUE" || w == "FALSE" => value.bools.push(w == "TRUE"),
            _ => return false,
        }
        self.pos += 1;
        true
    }

    fn field_value(&mut self, name: &str) -> Result<Value> {
        let mut value = Value::default();
        let next = self.peek().map(|t| t.kind.clone());
        match next {
            Some(TokenKind::OpenBracket) => {
                self.pos += 1;
                self.enter()?;
                loop {
                    let next = self.peek().map(|t| t.kind == TokenKind::CloseBracket);
                    match next {
                        Some(true) => {
                            self.pos += 1;
                            break;
                        }
                        None => {
                            return Err(self.error_here(format!(
                            "expected `]` to close the list of `{name}`, found the end of the file"
                        )))
                        }
                        _ if self.scalar(&mut value) => {}
                        _ if self.not_a_number(&value).is_some() => {
                            let found = self.not_a_number(&value).unwrap_or_default();
                            return Err(self.refuse_number(name, &value, &found));
                        }
                        _ if self.is_node_start() => value
                            .nodes
                            .extend(self.node_statement(&format!("the list `{name}`"))?),
                        _ => {
                            return Err(self.error_here(format!(
                                "expected a value or `]` in the list `{name}`, found {}",
                                describe(self.peek())
                            )))
                        }
                    }
                }
                self.depth -= 1;
            }
            Some(TokenKind::Word(w)) if w == "IS" => {
                // A PROTO body's `field IS name`: nothing to read in a world.
                self.pos += 1;
                self.expect_name("a PROTO field name after IS")?;
            }
            _ if self.is_node_start() => {
                value
                    .nodes
                    .extend(self.node_statement(&format!("the field `{name}`"))?);
            }
            _ => {
                if !self.scalar(&mut value) {
                    if let Some(found) = self.not_a_number(&value) {
                        return Err(self.refuse_number(name, &value, &found));
                    }
                    return Err(self.error_here(format!(
                        "expected a value for the field `{name}` (numbers, a string, TRUE/FALSE, a node or a [list]), found {}",
                        describe(self.peek())
                    )));
                }
                // A single-valued field or an MF field written without brackets.
                while self.scalar(&mut value) {}
                let found = self.not_a_number(&value);
                let non_finite =
                    matches!(self.peek().map(|t| &t.kind), Some(TokenKind::NotANumber(_)))
                        || found.as_deref().is_some_and(spells_non_finite);
                if !non_finite {
                    self.check_vector_length(name, &value)?;
                }
                if let Some(found) = found {
                    return Err(self.refuse_number(name, &value, &found));
                }
            }
        }
        Ok(value)
    }
}

/// The Webots base nodes whose frame fields are read as vectors of a fixed length (a PROTO may
/// give a field of the same name another type, so only these are checked).
const FRAME_NODES: [&str; 5] = ["Solid", "Robot", "Pose", "Transform", "E-puck"];

/// How many numbers the field `name` of a node of type `node` holds, when Webots fixes it:
/// `translation` (SFVec3f) and `rotation` (SFRotation) of [`FRAME_NODES`].
fn vector_length(node: &str, name: &str) -> Option<usize> {
    if !FRAME_NODES.contains(&node) {
        return None;
    }
    match name {
        "translation" => Some(3),
        "rotation" => Some(4),
        _ => None,
    }
}
