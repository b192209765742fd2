"""The VRML97 text of Webots worlds and PROTO bodies as a tree that keeps where each part is.

The PROTO engine rewrites text: it replaces an instance's span with its expansion and an ``IS``
reference with the value it stands for, so every node, field and value here records the
character span it came from. Field arity is not written in the file: a field keeps every value
(numbers, strings, booleans, nodes, brackets) up to the next field name, as the core's reader
does. ``#`` starts a comment outside strings; commas are white space.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import NamedTuple, TypeVar

from mazesim.errors import WorldFormatError

__all__ = [
    "Field",
    "Node",
    "Token",
    "first_value",
    "line_numbers",
    "line_of",
    "literal",
    "located_error",
    "nodes_in_order",
    "parse_nodes",
    "tokenize",
    "unix_line_ends",
    "world_version",
]

#: A token, a comment or (alone) a quote that opens a string never closed; white space, commas
#: and byte-order marks are what lies between.
_TOKEN = re.compile(
    r'(?P<string>"[^"\\]*(?:\\.[^"\\]*)*")|(?P<punct>[{}\[\]])|(?P<word>[^\s,"#{}\[\]\ufeff][^\s,"#{}\[\]]*)'
    r'|(?P<comment>#[^\n\r]*)|(?P<unclosed>")',
    re.DOTALL,
)
_HEADER = re.compile(r"#VRML_SIM\s+(R\d{4}[a-z]|V?\d+(?:\.\d+)*)")
#: A number as VRML97 writes it (no hexadecimal, infinity or NaN).
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_Value = TypeVar("_Value")


class Token(NamedTuple):
    """A token: its kind (``{``, ``}``, ``[``, ``]``, ``string`` or ``word``) and its span."""

    kind: str
    text: str
    start: int
    end: int

    def value(self) -> float | bool | str | None:
        """What the token stands for: a string's text (its escapes kept), else :func:`literal`
        of the word."""
        return self.text[1:-1] if self.kind == "string" else literal(self.text)


#: The words that stand for a flag or for no node.
_WORDS: dict[str, bool | None] = {
    "TRUE": True,
    "true": True,
    "FALSE": False,
    "false": False,
    "NULL": None,
}


def literal(word: str) -> float | bool | str | None:
    """What a bare word of a value stands for: ``TRUE``/``FALSE`` a flag, ``NULL`` None, a
    number (hexadecimal after ``0x``) a float; any other word is itself."""
    if word in _WORDS:
        return _WORDS[word]
    try:
        return float(word) if not word.lower().startswith(("0x", "-0x")) else float(int(word, 16))
    except ValueError:
        return word


def tokenize(text: str, source: str = "<text>") -> list[Token]:
    """Splits text into tokens, skipping white space, commas and comments.

    Raises:
        WorldFormatError: A string is not closed.
    """
    tokens: list[Token] = []
    add, make = tokens.append, Token._make  # the package's own values: no argument check
    for match in _TOKEN.finditer(text):
        kind = match.lastgroup
        if kind == "word" or kind == "string":
            add(make((kind, match.group(), *match.span())))
        elif kind == "punct":
            add(make((match.group(), match.group(), *match.span())))
        elif kind == "unclosed":
            message = "expected a closing '\"', found the end of the text"
            raise located_error(message, source, text, match.start())
    return tokens


def world_version(text: str) -> tuple[str | None, bool]:
    """The Webots release a world's ``#VRML_SIM`` header names (``R2023b``, ``V8.5``; None
    without a header), and whether its frame is the old NUE one, y up (before R2022a)."""
    found = _HEADER.search(text[:200])
    tag = found.group(1) if found else None
    return tag, tag is not None and (not tag.startswith("R") or tag < "R2022a")


def unix_line_ends(text: str) -> str:
    """The text with every line end (``\\r\\n`` or a lone ``\\r``) made ``\\n``, as the core's
    importer counts lines."""
    return text.replace("\r\n", "\n").replace("\r", "\n")


def line_numbers(text: str) -> Callable[[int], int]:
    """A function giving the 1-based line of a position of ``text`` (``\\n`` ends a line), by
    bisection over the line ends found once: for many positions of a long text, where
    counting the line ends before each anew takes time quadratic in its length."""
    ends = [found.start() for found in re.finditer("\n", text)]
    return lambda position: bisect.bisect_left(ends, position) + 1


def line_of(text: str, position: int) -> int:
    """The 1-based line of a position (``\\n``, ``\\r\\n`` or a lone ``\\r`` end a line)."""
    before = text[:position]
    return before.count("\n") + before.count("\r") - before.count("\r\n") + 1


def located_error(message: str, source: str, text: str = "", position: int = 0) -> WorldFormatError:
    """A ``WorldFormatError`` at a position of a text (line and column 1-based)."""
    line = line_of(text, position)
    start = max(text.rfind("\n", 0, position), text.rfind("\r", 0, position)) + 1
    column = position - start + 1
    return WorldFormatError(
        f"{source}:{line}:{column}: {message}", source=source, line=line, column=column
    )


@dataclass
class Field:
    """A field of a node: its name, its values (tokens and nodes in order) and its span."""

    name: str
    start: int
    end: int
    #: Nodes among the values, in order.
    nodes: list[Node] = field(default_factory=list)
    #: Tokens of the value that are not inside a node (numbers, strings, brackets, ``IS``).
    tokens: list[Token] = field(default_factory=list)
    #: The span of the value (after the name); empty when the field has no value.
    value_start: int = 0
    value_end: int = 0

    def numbers(self, count: int | None = None) -> tuple[float, ...] | None:
        """The first ``count`` values when they are numbers, or (for None) every value when
        they all are; None otherwise."""
        values = self.tokens if count is None else self.tokens[:count]
        if (count is None and self.nodes) or not values or len(values) < (count or 0):
            return None
        if not all(t.kind == "word" and _NUMBER.fullmatch(t.text) for t in values):
            return None
        return tuple(float(t.text) for t in values)

    def string(self) -> str | None:
        """The first value when it is a string, as written (its escapes kept); else None."""
        first = self.tokens[0] if self.tokens else None
        return first.text[1:-1] if first is not None and first.kind == "string" else None

    def flag(self) -> bool | None:
        """The first value when it is ``TRUE`` or ``FALSE``; else None."""
        first = self.tokens[0].text if self.tokens else None
        return None if first not in ("TRUE", "FALSE") else first == "TRUE"

    @property
    def is_reference(self) -> str | None:
        """The PROTO field this one stands for (``name IS other``), or None."""
        words = [t.text for t in self.tokens]
        if len(words) == 2 and words[0] == "IS":
            return words[1]
        return None


@dataclass
class Node:
    """A node: ``[DEF name] Type { fields }`` or ``USE name``, with its span."""

    type_name: str
    start: int
    end: int
    def_name: str | None = None
    use_name: str | None = None
    fields: list[Field] = field(default_factory=list)
    #: Where its type's name is (after ``DEF name``); its start for a ``USE``.
    type_start: int = 0

    def field(self, name: str) -> Field | None:
        """The field of that name (the last one when written twice)."""
        for candidate in reversed(self.fields):
            if candidate.name == name:
                return candidate
        return None

    def own_fields(self) -> Iterator[Field]:
        """The fields, but those a ``hidden`` word marks as engine state (a saved joint's
        ``hidden position_0_0 0.5``, written in a world after a run)."""
        hidden = False
        for item in self.fields:
            if item.name == "hidden" and not item.tokens and not item.nodes:
                hidden = True
                continue
            if not hidden:
                yield item
            hidden = False


def first_value(
    nodes: Iterable[Node], name: str, read: Callable[[Field], _Value | None]
) -> _Value | None:
    """What ``read`` finds in the first field of that name among the own fields of ``nodes``
    (in the order the text writes them) in which it finds something; None without one."""
    found = [
        (item.start, value)
        for node in nodes
        for item in node.own_fields()
        if item.name == name and (value := read(item)) is not None
    ]
    return min(found, key=lambda pair: pair[0])[1] if found else None


def nodes_in_order(nodes: Iterable[Node]) -> Iterator[Node]:
    """Every node of the trees ``nodes`` (``USE`` ones too), each before the nodes inside it, in
    the order the text writes them (without recursion, so at any depth)."""
    pending = list(reversed(list(nodes)))
    while pending:
        node = pending.pop()
        yield node
        for item in reversed(node.fields):
            pending.extend(reversed(item.nodes))


#: How deep the PROTO engine lets nodes nest (its walks over the tree recurse).
MAX_DEPTH = 200


def _extend(item: Field, start: int, end: int) -> None:
    """Extends a field's value over a token or node from ``start`` to ``end`` (its first, when
    the value is empty)."""
    if not item.tokens and not item.nodes:
        item.value_start = start
    item.value_end = end


class _Parser:
    """Reads nodes with a stack of the nodes and fields open (no recursion, so any depth)."""

    def __init__(self, text: str, tokens: list[Token], source: str) -> None:
        self.text, self.tokens, self.source = text, tokens, source
        self.index = 0

    def peek(self, offset: int = 0) -> Token | None:
        at = self.index + offset
        return self.tokens[at] if at < len(self.tokens) else None

    def fail(self, message: str) -> WorldFormatError:
        token = self.peek()
        position = token.start if token else len(self.text)
        return located_error(message, self.source, self.text, position)

    def starts_node(self) -> bool:
        token, after = self.peek(), self.peek(1)
        if token is None or token.kind != "word":
            return False
        if token.text in ("DEF",):
            return True
        if token.text == "USE":
            return after is not None and after.kind == "word"
        return after is not None and after.kind == "{"

    def opening(self) -> tuple[Node, bool]:
        """Reads a node's head (``USE name``, or ``[DEF name] Type {``); whether it has a body
        to read."""
        first = self.tokens[self.index]
        if first.text == "USE":
            used = self.tokens[self.index + 1]
            self.index += 2
            return Node(
                "USE", first.start, used.end, use_name=used.text, type_start=first.start
            ), False
        def_name = None
        if first.text == "DEF":
            name, kind = self.peek(1), self.peek(2)
            if name is None or kind is None or kind.kind != "word":
                raise self.fail("expected DEF NAME Type { ... }")
            def_name = name.text
            self.index += 2
        type_token = self.tokens[self.index]
        opening = self.peek(1)
        if opening is None or opening.kind != "{":
            raise self.fail(f"expected '{{' after {type_token.text}")
        self.index += 2
        node = Node(type_token.text, first.start, first.end, def_name, type_start=type_token.start)
        return node, True

    def node(self, max_depth: int | None) -> Node:
        """Reads the node that starts at the current token, nested at most ``max_depth`` deep
        (any depth for None)."""
        top, has_body = self.opening()
        # The nodes being read, outermost first, each with the field being read (or None).
        open_nodes: list[tuple[Node, Field | None]] = [(top, None)] if has_body else []
        while open_nodes:
            node, reading = open_nodes[-1]
            if reading is None:
                started = self.field_start(node)
                if started is not None:
                    open_nodes[-1] = (node, started)
                    continue
                open_nodes.pop()  # its '}' was read
                if open_nodes:
                    parent, parent_field = open_nodes[-1]
                    assert parent_field is not None
                    _extend(parent_field, node.start, node.end)
                    parent_field.nodes.append(node)
                continue
            if not self.field_values(reading):
                reading.end = reading.value_end
                open_nodes[-1] = (node, None)
                continue
            if max_depth is not None and len(open_nodes) > max_depth:
                raise self.fail(f"expected nodes nested at most {max_depth} deep")
            child, child_body = self.opening()
            if child_body:
                open_nodes.append((child, None))
            else:
                _extend(reading, child.start, child.end)
                reading.nodes.append(child)
        return top

    def field_start(self, node: Node) -> Field | None:
        """Reads the name of a node's next field whose value follows (a ``name IS other``
        field is read whole on the way); None when the node's ``}`` comes instead (read too)."""
        while (token := self.peek()) is not None and token.kind == "word":
            self.index += 1
            result = Field(token.text, token.start, token.end, value_start=token.end)
            result.value_end = token.end
            node.fields.append(result)
            reference, target = self.peek(), self.peek(1)
            if reference is None or reference.text != "IS" or reference.kind != "word":
                return result
            if target is None or target.kind != "word":
                raise self.fail("expected a field name after IS")
            result.tokens += [reference, target]
            self.index += 2
            result.value_start, result.value_end = reference.start, target.end
            result.end = target.end
        if token is None:
            raise self.fail(f"expected '}}' closing {node.type_name}, found the end")
        if token.kind != "}":
            raise self.fail(f"expected a field name in {node.type_name}, found {token.text}")
        self.index += 1
        node.end = token.end
        return None

    def field_values(self, reading: Field) -> bool:
        """Reads values of the field being read up to a node among them (True: a node starts
        at the current token) or to the field's end (False): a field keeps every value up to
        the next field name or the closing of its node."""
        tokens, index = self.tokens, self.index
        brackets = sum({"[": 1, "]": -1}.get(t.kind, 0) for t in reading.tokens)
        while index < len(tokens):
            token = tokens[index]
            self.index = index
            if token.kind == "word":
                after = tokens[index + 1].kind if index + 1 < len(tokens) else None
                if (token.text in ("DEF", "USE") or after == "{") and self.starts_node():
                    return True
                if not brackets and isinstance(literal(token.text), str):
                    return False
            elif token.kind in ("}", "]") and not brackets:
                return False
            elif token.kind in ("[", "]"):
                brackets += 1 if token.kind == "[" else -1
            elif token.kind == "}":
                raise self.fail("expected ']' before '}'")
            _extend(reading, token.start, token.end)
            reading.tokens.append(token)
            index += 1
        self.index = index
        return False


def parse_nodes(
    text: str,
    source: str = "<text>",
    start: int = 0,
    end: int | None = None,
    max_depth: int | None = MAX_DEPTH,
) -> list[Node]:
    """Parses the top-level nodes of a text (skipping ``EXTERNPROTO`` lines, ``PROTO``
    definitions written in a world and other words between).

    Args:
        text: The text.
        source: A name for error messages.
        start: Where to start reading.
        end: Where to stop (the end of the text by default).
        max_depth: How deep nodes may nest (:data:`MAX_DEPTH` by default); None for any depth.

    Raises:
        WorldFormatError: The text is not VRML97 nodes.
    """
    tokens = [
        t for t in tokenize(text[:end] if end is not None else text, source) if t.start >= start
    ]
    parser = _Parser(text, tokens, source)
    nodes: list[Node] = []
    while (token := parser.peek()) is not None:
        if parser.starts_node():
            nodes.append(parser.node(max_depth))
        elif token.text == "PROTO" and token.kind == "word":
            parser.index = _after_definition(tokens, parser.index)
        else:
            parser.index += 1
    return nodes


def _after_definition(tokens: list[Token], index: int) -> int:
    """The index after a ``PROTO Name [ interface ] { body }`` that starts at ``index`` (the
    next one's when the word ``PROTO`` starts no such definition)."""
    if index + 2 >= len(tokens) or tokens[index + 2].kind != "[":
        return index + 1
    index += 2
    for opening, closing in (("[", "]"), ("{", "}")):
        depth = 0
        while index < len(tokens) and (depth or tokens[index].kind == opening):
            depth += {opening: 1, closing: -1}.get(tokens[index].kind, 0)
            index += 1
    return index
