"""The VRML97 text of Webots worlds and PROTO bodies as a tree that keeps where each part is.

The PROTO engine rewrites text: it replaces an instance's span with its expansion and an ``IS``
reference with the value it stands for, so every node, field and value here records the
character span it came from. Field arity is not written in the file: a field keeps every value
(numbers, strings, booleans, nodes, brackets) up to the next field name, as the core's reader
does. ``#`` starts a comment outside strings; commas are white space.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from mazesim.errors import WorldFormatError

__all__ = ["Field", "Node", "Token", "line_of", "located_error", "parse_nodes", "tokenize"]

_TOKEN = re.compile(
    r'(?P<space>[\s,\ufeff]+)|(?P<comment>#[^\n\r]*)|(?P<string>"(?:[^"\\]|\\.)*")'
    r'|(?P<punct>[{}\[\]])|(?P<word>[^\s,"#{}\[\]]+)',
    re.DOTALL,
)


@dataclass(frozen=True)
class Token:
    """A token: its kind (``{``, ``}``, ``[``, ``]``, ``string`` or ``word``) and its span."""

    kind: str
    text: str
    start: int
    end: int


def tokenize(text: str, source: str = "<text>") -> list[Token]:
    """Splits text into tokens, skipping white space, commas and comments.

    Raises:
        WorldFormatError: A string is not closed.
    """
    tokens: list[Token] = []
    position = 0
    while position < len(text):
        match = _TOKEN.match(text, position)
        if match is None:  # an unclosed string
            raise _error(
                text, position, source, "expected a closing '\"', found the end of the text"
            )
        kind = match.lastgroup or "space"
        if kind == "string":
            tokens.append(Token("string", match.group(), match.start(), match.end()))
        elif kind == "punct":
            tokens.append(Token(match.group(), match.group(), match.start(), match.end()))
        elif kind == "word":
            tokens.append(Token("word", match.group(), match.start(), match.end()))
        position = match.end()
    return tokens


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


def _error(text: str, position: int, source: str, message: str) -> WorldFormatError:
    return located_error(message, source, text, position)


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

    def field(self, name: str) -> Field | None:
        """The field of that name (the last one when written twice)."""
        for candidate in reversed(self.fields):
            if candidate.name == name:
                return candidate
        return None


_MAX_DEPTH = 200


class _Parser:
    def __init__(self, text: str, tokens: list[Token], source: str) -> None:
        self.text, self.tokens, self.source = text, tokens, source
        self.index = 0

    def peek(self, offset: int = 0) -> Token | None:
        at = self.index + offset
        return self.tokens[at] if at < len(self.tokens) else None

    def fail(self, message: str) -> WorldFormatError:
        token = self.peek()
        position = token.start if token else len(self.text)
        return _error(self.text, position, self.source, message)

    def starts_node(self) -> bool:
        token, after = self.peek(), self.peek(1)
        if token is None or token.kind != "word":
            return False
        if token.text in ("DEF",):
            return True
        if token.text == "USE":
            return after is not None and after.kind == "word"
        return after is not None and after.kind == "{"

    def node(self, depth: int) -> Node:
        if depth > _MAX_DEPTH:
            raise self.fail(f"expected nodes nested at most {_MAX_DEPTH} deep")
        first = self.tokens[self.index]
        if first.text == "USE":
            used = self.tokens[self.index + 1]
            self.index += 2
            return Node("USE", first.start, used.end, use_name=used.text)
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
        node = Node(type_token.text, first.start, first.end, def_name=def_name)
        while True:
            token = self.peek()
            if token is None:
                raise self.fail(f"expected '}}' closing {type_token.text}, found the end")
            if token.kind == "}":
                self.index += 1
                node.end = token.end
                return node
            if token.kind != "word":
                raise self.fail(f"expected a field name in {type_token.text}, found {token.text}")
            node.fields.append(self.field(depth))

    def field(self, depth: int) -> Field:
        name = self.tokens[self.index]
        self.index += 1
        result = Field(name.text, name.start, name.end, value_start=name.end, value_end=name.end)
        token = self.peek()
        if token is not None and token.text == "IS" and token.kind == "word":
            target = self.peek(1)
            if target is None or target.kind != "word":
                raise self.fail("expected a field name after IS")
            result.tokens += [token, target]
            self.index += 2
            result.value_start, result.value_end = token.start, target.end
            result.end = target.end
            return result
        bracket = 0
        first = True
        while (token := self.peek()) is not None:
            if bracket == 0 and (
                token.kind in ("}", "]")
                or (token.kind == "word" and not _is_literal(token.text) and not self.starts_node())
            ):
                break
            if self.starts_node():
                child = self.node(depth + 1)
                result.nodes.append(child)
                end = child.end
            else:
                if token.kind == "[":
                    bracket += 1
                elif token.kind == "]":
                    bracket -= 1
                elif token.kind == "}":
                    raise self.fail("expected ']' before '}'")
                result.tokens.append(token)
                self.index += 1
                end = token.end
            if first:
                result.value_start = token.start
                first = False
            result.value_end = end
        result.end = result.value_end
        return result


def _is_literal(word: str) -> bool:
    if word in ("TRUE", "FALSE", "NULL", "true", "false"):
        return True
    try:
        float(word) if not word.lower().startswith(("0x", "-0x")) else int(word, 16)
    except ValueError:
        return False
    return True


def parse_nodes(
    text: str, source: str = "<text>", start: int = 0, end: int | None = None
) -> list[Node]:
    """Parses the top-level nodes of a text (skipping ``EXTERNPROTO`` lines and words between).

    Args:
        text: The text.
        source: A name for error messages.
        start: Where to start reading.
        end: Where to stop (the end of the text by default).

    Raises:
        WorldFormatError: The text is not VRML97 nodes.
    """
    tokens = [
        t for t in tokenize(text[:end] if end is not None else text, source) if t.start >= start
    ]
    parser = _Parser(text, tokens, source)
    nodes: list[Node] = []
    while parser.peek() is not None:
        if parser.starts_node():
            nodes.append(parser.node(0))
        else:
            parser.index += 1
    return nodes
