"""A PROTO file read: its interface (fields with types and default values), its body and the
template language of a procedural body (JavaScript since Webots R2022b, Lua before)."""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from .syntax import located_error, tokenize, unix_line_ends

__all__ = ["FieldDeclaration", "ProtoDefinition", "parse_definition", "externproto_urls"]

_DECLARATIONS = ("field", "hiddenField", "vrmlField", "unconnectedField", "exposedField")
_EXTERNPROTO = re.compile(r'^\s*(?:IMPORTABLE\s+)?EXTERNPROTO\s+"([^"]*)"', re.MULTILINE)


@dataclass(frozen=True)
class FieldDeclaration:
    """A field of a PROTO's interface: its VRML type (``SFVec3f``...), name and default text."""

    kind: str
    name: str
    default: str


@dataclass
class ProtoDefinition:
    """A PROTO: its name, fields, body text, template language and where it was read from."""

    name: str
    fields: dict[str, FieldDeclaration]
    body: str
    #: ``"javascript"``, ``"lua"`` or None for a body without templates.
    language: str | None
    #: The file or URL it was read from.
    origin: str
    #: Its own ``EXTERNPROTO`` URLs, by PROTO name.
    externprotos: dict[str, str] = field(default_factory=dict)


def externproto_urls(text: str) -> dict[str, str]:
    """The ``EXTERNPROTO`` declarations of a world or PROTO file, by PROTO name (file stem)."""
    urls: dict[str, str] = {}
    for url in _EXTERNPROTO.findall(text):
        stem = url.rsplit("/", 1)[-1]
        if stem.endswith(".proto"):
            urls.setdefault(stem[: -len(".proto")], url)
    return urls


def _language(text: str, body: str) -> str | None:
    header = re.search(r"^#\s*template language\s*:\s*(\w+)", text, re.MULTILINE | re.IGNORECASE)
    if header:
        return "javascript" if header.group(1).lower().startswith("java") else "lua"
    if "%<" in body:
        return "javascript"
    if "%{" in body:
        return "lua"
    return None


def parse_definition(text: str, origin: str) -> ProtoDefinition:
    """Reads a PROTO file's text.

    Args:
        text: The file's text.
        origin: The file or URL, for messages.

    Raises:
        WorldFormatError: The text has no ``PROTO Name [ ... ] { ... }``.
    """
    text = unix_line_ends(text)
    match = re.search(r"^\s*PROTO\s+([^\s\[]+)\s*\[", text, re.MULTILINE)
    if match is None:
        raise located_error("expected a PROTO definition (PROTO Name [ ... ] { ... })", origin)
    name = match.group(1)
    start = match.end()
    # The interface holds no template: its tokens can be read up to the closing ']'.
    tokens = tokenize(text[start:], origin)
    depth, end_index = 0, None
    for index, token in enumerate(tokens):
        if token.kind in ("[", "{"):
            depth += 1
        elif token.kind in ("]", "}"):
            if depth == 0:
                end_index = index
                break
            depth -= 1
    if end_index is None or tokens[end_index].kind != "]":
        raise located_error(f"PROTO {name}: expected ']' closing its fields", origin)
    interface_end = start + tokens[end_index].start
    fields = _declarations(text, start, tokens[:end_index])
    opening = text.find("{", interface_end + 1)
    closing = _body_end(text)
    if opening < 0 or closing <= opening:
        raise located_error(f"PROTO {name}: expected '{{' body '}}' after its fields", origin)
    body = text[opening + 1 : closing]
    return ProtoDefinition(
        name=name,
        fields=fields,
        body=body,
        language=_language(text[:opening], body),
        origin=origin,
        externprotos=externproto_urls(text[: match.start()]),
    )


def _body_end(text: str) -> int:
    """The position of the body's closing brace: the last '}' outside trailing comments."""
    lines = text.split("\n")
    offset = len(text)
    for line in reversed(lines):
        offset -= len(line)
        stripped = line.strip()
        if stripped and not stripped.startswith("#"):
            position = line.rfind("}")
            if position >= 0:
                return offset + position
        offset -= 1
    return -1


def _declarations(text: str, base: int, tokens: list) -> dict[str, FieldDeclaration]:
    fields: dict[str, FieldDeclaration] = {}
    starts = [
        i
        for i, t in enumerate(tokens)
        if t.kind == "word" and t.text in _DECLARATIONS and _at_top(tokens, i)
    ]
    for number, index in enumerate(starts):
        stop = starts[number + 1] if number + 1 < len(starts) else len(tokens)
        part = tokens[index + 1 : stop]
        if not part:
            continue
        kind = part[0].text
        cursor = 1
        if cursor < len(part) and part[cursor].kind == "{":  # a value restriction
            depth = 0
            while cursor < len(part):
                depth += {"{": 1, "}": -1}.get(part[cursor].kind, 0)
                cursor += 1
                if depth == 0:
                    break
        if cursor >= len(part):
            continue
        name_token = part[cursor]
        rest = part[cursor + 1 :]
        default = text[base + rest[0].start : base + rest[-1].end] if rest else ""
        fields[name_token.text] = FieldDeclaration(kind.split("{")[0], name_token.text, default)
    return fields


def _at_top(tokens: list, index: int) -> bool:
    depth = 0
    for token in tokens[:index]:
        if token.kind in ("[", "{"):
            depth += 1
        elif token.kind in ("]", "}"):
            depth -= 1
    return depth == 0
