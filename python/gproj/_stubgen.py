"""Writes the package's type stubs, `__init__.pyi`, from the registry.

    python3 -m gproj._stubgen [OUT.pyi]     (default: print to stdout)
    python3 -m gproj._stubgen --core STUBGEN.pyi [OUT.pyi]

The stubs declare every problem's function (its signature with the schema's types and
defaults), options class and result class, and re-export the typed pure-Python classes and the
extension's own (whose stubs, `_core.pyi`, are written by mypy's stubgen from the extension,
`stubgen -p gproj._core`, and completed by `--core`: stubgen leaves a function whose signature
has keyword-only arguments as `(*args, **kwargs) -> Any`, and `--core` writes it from the
signature line of its docstring). The test suite checks that the shipped stubs are the ones
these write, and type-checks a script against them with mypy.
"""

from __future__ import annotations

import re
import sys
from typing import Any, List, Mapping, Optional

from gproj import _core
from gproj._problems import (Parameter, camel, docstring, main_output, option_annotation,
                             option_doc, parameters, result_fields)

HEADER = '''# Generated from the registry by `python3 -m gproj._stubgen`; do not edit.
import os
from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
from numpy.typing import ArrayLike

from gproj._core import Problem as Problem
from gproj._core import schema as schema
from gproj._utilities import bspline_curvature as bspline_curvature
from gproj._utilities import face_values as face_values
from gproj._utilities import read_mesh as read_mesh
from gproj._utilities import write_mesh as write_mesh
from gproj._problems import GprojWarning as GprojWarning
from gproj._results import Mesh as Mesh
from gproj._results import Report as Report
from gproj._results import Result as Result

__version__: str

def run(problem: str, *args: Any, **kwargs: Any) -> Result: ...
'''


def _default(value: Any) -> str:
    if value is None or isinstance(value, (bool, int, float, str)):
        return repr(value)
    if value == ():
        return "()"
    return "..."


def _parameter(p: Parameter) -> str:
    import inspect

    if p.default is inspect.Parameter.empty:
        return f"{p.name}: {p.annotation}"
    return f"{p.name}: {p.annotation} = {_default(p.default)}"


def _function(spec: Mapping[str, Any]) -> List[str]:
    params = parameters(spec)
    positional = [_parameter(p) for p in params if p.positional]
    keyword = [_parameter(p) for p in params if not p.positional]
    returns = "Mesh" if spec["generator"] else f"{camel(spec['name'])}Result"
    args = positional + (["*"] + keyword if keyword else [])
    doc = docstring(spec).replace("\\", "\\\\").replace('"""', "'''")
    lines = [f"def {spec['name']}("]
    lines += [f"    {a}," for a in args]
    lines += [f") -> {returns}:", f'    """{doc}"""', "    ..."]
    return lines


def _options(spec: Mapping[str, Any]) -> List[str]:
    name = f"{camel(spec['name'])}Options"
    lines = [f"class {name}:", f'    """The options of {spec["name"]}()."""']
    init = ["        self,", "        *,"]
    for o in spec["options"]:
        annotation = option_annotation(o)
        lines.append(f"    {o['name']}: {annotation}")
        lines.append(f'    """{option_doc(o)}"""'.replace("\\", "\\\\"))
        default = "" if o.get("required") else f" = {_default(o['default'])}"
        init.append(f"        {o['name']}: {annotation}{default},")
    if spec["options"]:
        lines += ["    def __init__("] + init + ["    ) -> None: ..."]
    return lines


def _result(spec: Mapping[str, Any]) -> List[str]:
    out = main_output(spec)
    lines = [f"class {camel(spec['name'])}Result(Result):",
             f'    """The result of {spec["name"]}(): {out["doc"]}."""']
    if out["kind"] == "mesh":
        lines += ["    output: Optional[Mesh]"]
    elif out["kind"] == "json":
        lines += ["    output: Optional[Dict[str, Any]]"]
    else:
        lines += ["    output: Optional[str]"]
    for name, annotation, doc in result_fields(spec):
        lines += [f"    {name}: {annotation}", f'    """{doc}"""']
    return lines


def stubs() -> str:
    parts = [HEADER]
    for spec in _core.schema()["problems"]:
        if not spec["generator"]:
            parts.append("\n".join(_options(spec)) + "\n")
            parts.append("\n".join(_result(spec)) + "\n")
        parts.append("\n".join(_function(spec)) + "\n")
    return "\n".join(parts)


def _split_top_level(text: str) -> List[str]:
    """`text` split at the commas outside brackets and quotes."""
    parts, depth, quote, start = [], 0, "", 0
    for i, c in enumerate(text):
        if quote:
            quote = "" if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            parts.append(text[start:i].strip())
            start = i + 1
    if text[start:].strip():
        parts.append(text[start:].strip())
    return parts


def _stub_signature(doc: Optional[str], method: bool) -> Optional[str]:
    """The stub's `(params) -> type` from a pybind11 docstring's first line, with the module
    prefix dropped and the defaults as `...` (None: no single signature there)."""
    if not doc:
        return None
    match = re.match(r"\w+\((.*)\) -> (.+)$", doc.split("\n", 1)[0])
    if match is None:
        return None
    params = []
    for i, part in enumerate(_split_top_level(match.group(1))):
        if method and i == 0:
            params.append("self")
            continue
        if part == "*":
            params.append(part)
            continue
        name, _, rest = part.partition(":")
        annotation, equals, _default_value = rest.partition("=")
        annotation = annotation.strip().replace("gproj._core.", "")
        params.append(f"{name.strip()}: {annotation}" + (" = ..." if equals else ""))
    returns = match.group(2).strip().replace("gproj._core.", "")
    return f"({', '.join(params)}) -> {returns}"


def core_stubs(stubgen_text: str) -> str:
    """mypy stubgen's `_core.pyi` with each `([self, ]*args, **kwargs) -> Any` written out."""
    lines, owner = [], None
    for line in stubgen_text.splitlines():
        klass = re.match(r"class (\w+)", line)
        if klass:
            owner = getattr(_core, klass.group(1))
        elif line and not line.startswith(" "):
            owner = None
        blank = re.match(r"(\s*)def (\w+)\((?:self, )?\*args, \*\*kwargs\) -> Any: \.\.\.$", line)
        if blank:
            indent, name = blank.groups()
            method = bool(indent)
            target = getattr(owner if method else _core, name)
            signature = _stub_signature(target.__doc__, method)
            if signature is not None:
                line = f"{indent}def {name}{signature}: ..."
        lines.append(line)
    return "\n".join(lines) + "\n"


def main(argv: List[str]) -> int:
    if len(argv) > 2 and argv[1] == "--core":
        with open(argv[2], encoding="utf-8") as f:
            text = core_stubs(f.read())
        argv = argv[2:]
    else:
        text = stubs()
    if len(argv) > 1:
        with open(argv[1], "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
