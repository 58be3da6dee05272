"""The registry's problems as Python functions, options classes and result classes.

Everything here is generated from the registry (`gproj schema`): one function per problem with a
real signature (names, defaults and docs from the schema), an options dataclass per problem
(`PlanarizeOptions`, ...) and a result class per problem (`PlanarizeResult`, ...). The stubs in
`__init__.pyi` are generated from the same description (`python3 -m gproj._stubgen`).
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import inspect
import os
import warnings
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from gproj import _core
from gproj._results import Mesh, Report, Result


class GprojWarning(UserWarning):
    """A run's warning: far from the asked net, bounds active, tolerance missed, ..."""


def camel(name: str) -> str:
    """'mrevolution' -> 'Mrevolution', 'hnet' -> 'Hnet', 'face_values' -> 'FaceValues'."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_"))


# --- Python types of the schema's kinds, as annotations (the stubs use the same text) ---------

_OPTION_TYPES = {
    "bool": "bool",
    "int": "int",
    "number": "float",
    "numbers": "Sequence[float]",
    "points": "ArrayLike",
    "ints": "Sequence[int]",
    "vertex_values": "Union[Mapping[int, float], Sequence[Tuple[int, float]]]",
}

_KEYWORD_INPUT_TYPES = {
    "mesh": "Optional[Tuple[ArrayLike, ArrayLike]]",
    "quad_mesh": "Optional[Tuple[ArrayLike, ArrayLike]]",
    "vertex_ids": "Union[ArrayLike, str, os.PathLike[str], None]",
    "curve": "Union[ArrayLike, str, os.PathLike[str], None]",
    "bspline": "Union[Mapping[str, Any], str, os.PathLike[str], None]",
    "text": "Union[str, os.PathLike[str], None]",
    "json": "Union[Mapping[str, Any], str, os.PathLike[str], None]",
}

_POSITIONAL_INPUT_TYPES = {
    "curve": "Union[ArrayLike, str, os.PathLike[str]]",
    "bspline": "Union[Mapping[str, Any], str, os.PathLike[str]]",
    "text": "Union[str, os.PathLike[str]]",
    "json": "Union[Mapping[str, Any], str, os.PathLike[str]]",
}

_OUTPUT_TYPES = {"mesh": "Optional[Mesh]", "json": "Optional[Dict[str, Any]]"}


def option_annotation(option: Mapping[str, Any]) -> str:
    if option["type"] == "choice":
        text = "Literal[" + ", ".join(repr(c) for c in option["choices"]) + "]"
    else:
        text = _OPTION_TYPES[option["type"]]
    return f"Optional[{text}]" if option["default"] is None and not option.get("required") else text


def positional_inputs(spec: Mapping[str, Any]) -> List[Mapping[str, Any]]:
    return [i for i in spec["inputs"] if i["positional"]]


def keyword_inputs(spec: Mapping[str, Any]) -> List[Mapping[str, Any]]:
    return [i for i in spec["inputs"] if not i["positional"]]


def is_mesh_kind(kind: str) -> bool:
    return kind in ("mesh", "quad_mesh")


def has_mesh_input(spec: Mapping[str, Any]) -> bool:
    return any(is_mesh_kind(i["kind"]) for i in spec["inputs"])


def main_output(spec: Mapping[str, Any]) -> Mapping[str, Any]:
    output: Mapping[str, Any] = spec["outputs"][0]
    return output


class Parameter:
    """One parameter of a problem's function: its name, annotation text, default and doc."""

    def __init__(self, name: str, annotation: str, doc: str, default: Any = inspect.Parameter.empty,
                 positional: bool = False):
        self.name, self.annotation, self.doc = name, annotation, doc
        self.default, self.positional = default, positional

    def inspect_parameter(self) -> inspect.Parameter:
        kind = (inspect.Parameter.POSITIONAL_OR_KEYWORD if self.positional else
                inspect.Parameter.KEYWORD_ONLY)
        return inspect.Parameter(self.name, kind, default=self.default,
                                 annotation=self.annotation)


def _number_text(value: float) -> str:
    """Whole numbers in full (a seed's 4294967295), others shortest: 59.9, 1e-12."""
    if float(value).is_integer() and abs(value) < 1e16:
        return str(int(value))
    return repr(float(value))


def _range_text(option: Mapping[str, Any]) -> str:
    parts = []
    if "minimum" in option:
        parts.append((">" if option["minimum_exclusive"] else ">=") +
                     f" {_number_text(option['minimum'])}")
    if "maximum" in option:
        parts.append(("<" if option["maximum_exclusive"] else "<=") +
                     f" {_number_text(option['maximum'])}")
    if option.get("count"):
        parts.append(f"{option['count']} values")
    return ", ".join(parts)


def option_doc(option: Mapping[str, Any]) -> str:
    extras = [option["type"]]
    if option.get("unit"):
        extras.append(option["unit"])
    if _range_text(option):
        extras.append(_range_text(option))
    if option.get("required"):
        extras.append("required")
    return f"({', '.join(extras)}) {option['doc']}."


def parameters(spec: Mapping[str, Any]) -> List[Parameter]:
    """The function's parameters: (V, F) per positional mesh, the other positional inputs, then
    keyword-only: options=, the keyword inputs, the options, outputs= and callback=."""
    out: List[Parameter] = []
    for i in positional_inputs(spec):
        default = inspect.Parameter.empty if i["required"] else None
        optional = "" if i["required"] else " (optional)"
        if is_mesh_kind(i["kind"]):
            out.append(Parameter("V", "ArrayLike" if i["required"] else "Optional[ArrayLike]",
                                 f"the {i['name']}{optional}: (n, 3) float vertex positions. "
                                 f"{i['doc']}.", default, True))
            out.append(Parameter("F", "ArrayLike" if i["required"] else "Optional[ArrayLike]",
                                 f"(m, k) integer faces, 0-based (a list of faces for mixed "
                                 f"sizes).", default, True))
        else:
            annotation = _POSITIONAL_INPUT_TYPES[i["kind"]]
            out.append(Parameter(i["name"], annotation if i["required"] else
                                 f"Optional[{annotation}]", f"{i['doc']}{optional}.", default,
                                 True))
    if spec["generator"]:
        for o in spec["options"]:
            out.append(Parameter(o["name"], option_annotation(o), option_doc(o),
                                 inspect.Parameter.empty if o.get("required") else o["default"]))
        return out
    out.append(Parameter("options", f"Optional[{camel(spec['name'])}Options]",
                         f"a {camel(spec['name'])}Options; keyword arguments override its "
                         "fields.", None))
    for i in keyword_inputs(spec):
        out.append(Parameter(i["name"], _KEYWORD_INPUT_TYPES[i["kind"]], _input_doc(i), None))
    if has_mesh_input(spec):
        out.append(Parameter("weld", "bool", "merge the input meshes' coincident vertices "
                             "(within 1e-9 of the bounding-box diagonal) first, as unwelded "
                             "exports need; without it such a mesh is refused. Vertex ids (fixed, "
                             "...) then number the welded mesh; result.weld_map maps each input "
                             "vertex to it.", False))
    for o in spec["options"]:
        out.append(Parameter(o["name"], option_annotation(o), option_doc(o),
                             inspect.Parameter.empty if o.get("required") else o["default"]))
    optional = ", ".join(o["name"] for o in spec["outputs"] if not o["required"]) or "none"
    out.append(Parameter("outputs", "Sequence[str]",
                         f"optional outputs to make as well ({optional}); each is an attribute "
                         "of the result.", ()))
    out.append(Parameter("callback", "Optional[Callable[[Dict[str, Any]], Optional[bool]]]",
                         "called with each iteration record (the keys of report.history's "
                         "entries); returning False stops the run (status USER_ABORT). Ctrl-C "
                         "stops it too and raises KeyboardInterrupt.", None))
    return out


def _input_doc(i: Mapping[str, Any]) -> str:
    what = {
        "vertex_ids": "0-based vertex ids, a boolean mask over the vertices, or the path of "
                      "a file of ids",
        "curve": "an (n, 3) array of points, or the path of a text file of x y z lines",
        "bspline": "a dict, the B-spline's JSON, or the path of its .json file",
        "text": "a path (pathlib.Path or str naming a file) or the file's text",
        "json": "a dict (e.g. another run's output), its JSON text, or the path of its .json file",
    }.get(i["kind"], "a mesh (V, F)")
    return f"{what}. {i['doc']}."


def result_fields(spec: Mapping[str, Any]) -> List[Tuple[str, str, str]]:
    """(name, annotation, doc) of the result's attributes beyond Result's own."""
    fields = []
    for o in spec["outputs"][1:]:
        fields.append((o["name"], _OUTPUT_TYPES.get(o["kind"], "Optional[str]"),
                       f"{o['doc']} (None unless asked in outputs=)"))
    for a in spec["arrays"]:
        fields.append((a["name"], "Optional[npt.NDArray[np.float64]]", a["doc"]))
    return fields


def docstring(spec: Mapping[str, Any]) -> str:
    lines = [spec["summary"], ""]
    if not spec["generator"]:
        lines += ["Arguments:"]
    for p in parameters(spec):
        lines.append(f"    {p.name}: {p.doc}")
    if spec["generator"]:
        lines += ["", "Returns a Mesh (V, F): (n, 3) float64 vertices and (m, 4) int32 faces."]
    else:
        out = main_output(spec)
        what = ("`vertices` and `faces` (the mesh)" if out["kind"] == "mesh" else
                "`output` (a dict)" if out["kind"] == "json" else "`output` (text)")
        lines += [
            "",
            f"Returns a {camel(spec['name'])}Result: `report` (a Report: status, converged, "
            f"iterations, history, initial and final measures, options), {what}: "
            f"{out['doc']}, and"]
        for name, _, doc in result_fields(spec):
            lines.append(f"    {name}: {doc}")
        lines += [
            "When the run fails numerically, the result's mesh and outputs are None and "
            "report.status is FAILURE.",
            "",
            "Raises TypeError or ValueError naming the argument for bad arguments; warns "
            "(GprojWarning) when the input is far from the asked net or the result needs "
            "attention."]
    return "\n".join(lines) + "\n"


# --- Options classes -------------------------------------------------------------------------

def _options_class(spec: Mapping[str, Any]) -> type:
    name = spec["name"]
    fields: List[Any] = []
    for o in spec["options"]:
        if o.get("required"):
            fields.append((o["name"], Any))
        elif isinstance(o["default"], list):
            fields.append((o["name"], Any, dataclasses.field(
                default_factory=functools.partial(list, o["default"]))))
        else:
            fields.append((o["name"], Any, dataclasses.field(default=o["default"])))

    def post_init(self: Any) -> None:
        _core._check_options(name, dataclasses.asdict(self))

    cls = dataclasses.make_dataclass(
        f"{camel(name)}Options", fields, kw_only=True, namespace={"__post_init__": post_init})
    cls.__module__ = "gproj"
    cls.__doc__ = (f"The options of {name}() (checked when made; the same names, defaults and "
                   f"ranges as the function's keyword arguments):\n\n" +
                   "\n".join(f"    {o['name']}: {option_doc(o)}" for o in spec["options"]))
    return cls


def _result_class(spec: Mapping[str, Any]) -> type:
    namespace: Dict[str, Any] = {n: None for n, _, _ in result_fields(spec)}
    namespace["problem"] = spec["name"]
    namespace["__doc__"] = f"The result of {spec['name']}(); see Result.\n"
    namespace["__module__"] = "gproj"
    return type(f"{camel(spec['name'])}Result", (Result,), namespace)


# --- Calls -----------------------------------------------------------------------------------

def _text_input(name: str, value: Any) -> str:
    """A text input: a path (os.PathLike, or a str naming an existing file and no newline) is
    read; another str is the file's text."""
    if isinstance(value, os.PathLike) or (isinstance(value, str) and "\n" not in value and
                                          value.strip() and os.path.isfile(value)):
        try:
            with open(value, encoding="utf-8") as f:
                return f.read()
        except OSError as e:
            raise ValueError(f"{name}: cannot read {os.fspath(value)}: {e.strerror}") from None
        except UnicodeDecodeError:
            raise ValueError(f"{name}: {os.fspath(value)} is not a UTF-8 text file") from None
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected a path or the file's text (str), not "
                        f"{type(value).__name__}")
    return value


def _unknown_keyword(function: str, error: TypeError, names: Sequence[str]) -> TypeError:
    text = str(error)
    marker = "unexpected keyword argument '"
    if marker in text:
        bad = text.split(marker, 1)[1].rstrip("'")
        close = difflib.get_close_matches(bad, names, n=3)
        hint = f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else ""
        return TypeError(f"{function}() has no argument '{bad}'{hint}")
    return TypeError(f"{function}(): {text}")


class _Problem:
    """The function of one problem: binds the arguments to the schema's signature, runs the
    problem in the library and wraps the result."""

    def __init__(self, spec: Mapping[str, Any], options_class: Optional[type],
                 result_class: Optional[type]):
        self.spec, self.options_class, self.result_class = spec, options_class, result_class
        self.params = parameters(spec)
        self.signature = inspect.Signature([p.inspect_parameter() for p in self.params])
        self.option_names = {o["name"] for o in spec["options"]}

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        name = self.spec["name"]
        try:  # partial: a required option may come in options=
            bound = self.signature.bind_partial(*args, **kwargs)
        except TypeError as e:
            raise _unknown_keyword(name, e, [p.name for p in self.params]) from None
        given = bound.arguments
        positional: List[Any] = []
        for i in positional_inputs(self.spec):
            if is_mesh_kind(i["kind"]):
                if given.get("V") is None:
                    break
                if given.get("F") is None:
                    raise TypeError(f"{name}() needs the arrays V and F of its {i['name']}")
                positional += [given["V"], given["F"]]
            elif given.get(i["name"]) is not None:
                value = given[i["name"]]
                positional.append(_text_input(i["name"], value) if i["kind"] == "text" else value)
        options: Dict[str, Any] = {}
        keywords: Dict[str, Any] = {}
        base = given.get("options")
        if base is not None:
            if self.options_class is not None and isinstance(base, self.options_class):
                options.update(dataclasses.asdict(base))
            elif isinstance(base, Mapping):
                options.update(base)
            else:
                raise TypeError(f"options: expected a {camel(name)}Options or a dict, not "
                                f"{type(base).__name__}")
        for i in keyword_inputs(self.spec):
            if given.get(i["name"]) is not None:
                value = given[i["name"]]
                keywords[i["name"]] = (_text_input(i["name"], value) if i["kind"] == "text" else
                                       value)
        for key, value in given.items():
            if key in self.option_names:
                options[key] = value
        for key in [k for k, v in options.items() if v is None]:
            del options[key]  # None: the option's default (its absence)
        for o in self.spec["options"]:
            if o.get("required") and o["name"] not in options:
                raise TypeError(f"{name}(): missing the required option '{o['name']}'")
        for i in positional_inputs(self.spec):
            if i["required"] and not is_mesh_kind(i["kind"]) and given.get(i["name"]) is None:
                raise TypeError(f"{name}(): missing the required argument '{i['name']}'")
        weld = given.get("weld", False)
        if not isinstance(weld, bool):
            raise TypeError(f"weld: expected a bool, not {type(weld).__name__}")
        outputs = given.get("outputs", ())
        if isinstance(outputs, str):
            raise TypeError("outputs: expected a sequence of output names, not str")
        raw = _core._run(name, tuple(positional), options, keywords, list(outputs),
                         given.get("callback"), weld)
        return self.wrap(raw)

    def wrap(self, raw: Tuple[Any, ...]) -> Any:
        """The result of a run from what _core._run or _core._resolve gives back."""
        name = self.spec["name"]
        meshes_and_texts, arrays, report, messages, weld_maps, warm = raw
        for message in messages:
            warnings.warn(f"{name}: {message}", GprojWarning, stacklevel=4)
        if self.spec["generator"]:
            return Mesh(*meshes_and_texts[main_output(self.spec)["name"]])
        values = {k: Mesh(*v) if isinstance(v, tuple) else v for k, v in meshes_and_texts.items()}
        main = values.pop(main_output(self.spec)["name"], None)
        assert self.result_class is not None
        result = self.result_class(Report(report), main, values, arrays)
        result.weld_maps = dict(weld_maps)
        first = next((i["name"] for i in self.spec["inputs"] if is_mesh_kind(i["kind"])), None)
        result.weld_map = result.weld_maps.get(first) if first else None
        result._warm = (self, warm) if warm is not None else None
        return result

    def resolve(self, warm: Any, num_vertices: int, moved: Any, fixed: Any, soft_terms: bool,
                callback: Any, options: Dict[str, Any]) -> Any:
        """Result.resolve's run (see there)."""
        name = self.spec["name"]

        def vertex_id(value: Any, what: str) -> int:
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
                raise TypeError(f"{what}: vertex ids are integers, not {value!r}")
            if not 0 <= int(value) < num_vertices:
                raise ValueError(f"{what}: vertex {int(value)} is out of range (the mesh has "
                                 f"{num_vertices} vertices)")
            return int(value)

        def point(value: Any, vertex: int) -> List[float]:
            try:
                p = np.asarray(value, dtype=float)
            except (TypeError, ValueError):
                raise TypeError(f"moved: vertex {vertex}: expected a point (x, y, z) of numbers"
                                ) from None
            if p.shape != (3,):
                raise ValueError(f"moved: vertex {vertex}: expected a point (x, y, z), "
                                 f"got shape {p.shape}")
            return [float(c) for c in p]

        ids: List[int] = []
        to: List[List[float]] = []
        if moved is not None:
            if isinstance(moved, Mapping):
                pairs = list(moved.items())
            elif isinstance(moved, tuple) and len(moved) == 2:
                given_ids = np.asarray(moved[0]).reshape(-1).tolist()
                try:
                    positions = np.asarray(moved[1], dtype=float)
                except (TypeError, ValueError):
                    raise TypeError("moved: the positions are not numbers") from None
                if positions.shape != (len(given_ids), 3):
                    raise ValueError(f"moved: {len(given_ids)} ids but positions of shape "
                                     f"{positions.shape} (expected ({len(given_ids)}, 3))")
                pairs = list(zip(given_ids, positions))
            else:
                raise TypeError("moved: expected {vertex: (x, y, z)} or (ids, positions), not "
                                f"{type(moved).__name__}")
            for vertex, position in pairs:
                v = vertex_id(vertex, "moved")
                ids.append(v)
                to.append(point(position, v))
        held: List[int] = []
        if fixed is not None:
            array = np.asarray(fixed)
            if array.dtype == bool:
                if array.shape != (num_vertices,):
                    raise ValueError(f"fixed: a mask has one entry per vertex ({num_vertices}), "
                                     f"not shape {array.shape}")
                held = [int(v) for v in np.flatnonzero(array)]
            else:
                held = [vertex_id(v, "fixed") for v in array.reshape(-1).tolist()]
        if not isinstance(soft_terms, bool):
            raise TypeError(f"soft_terms: expected a bool, not {type(soft_terms).__name__}")
        for key in options:
            if key not in self.option_names:
                close = difflib.get_close_matches(key, sorted(self.option_names), n=3)
                hint = f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else ""
                raise TypeError(f"{name}: resolve() has no option '{key}'{hint}")
        return self.wrap(_core._resolve(warm, ids, to, held, options, soft_terms, callback))


def make_problems() -> Tuple[Dict[str, Callable[..., Any]], Dict[str, type], Dict[str, type]]:
    """(functions, options classes, result classes) by name, for every problem of the
    registry."""
    functions: Dict[str, Callable[..., Any]] = {}
    options: Dict[str, type] = {}
    results: Dict[str, type] = {}
    for spec in _core.schema()["problems"]:
        options_class = result_class = None
        if not spec["generator"]:
            options_class = _options_class(spec)
            result_class = _result_class(spec)
            options[options_class.__name__] = options_class
            results[result_class.__name__] = result_class
        problem = _Problem(spec, options_class, result_class)

        def function(*args: Any, _problem: _Problem = problem, **kwargs: Any) -> Any:
            return _problem(*args, **kwargs)

        function.__name__ = function.__qualname__ = spec["name"]
        function.__module__ = "gproj"
        function.__doc__ = docstring(spec)
        function.__signature__ = problem.signature  # type: ignore[attr-defined]
        functions[spec["name"]] = function
    return functions, options, results


def run(problem: str, *args: Any, **kwargs: Any) -> Any:
    """run(problem, *args, **kwargs): the function of the problem named `problem` (e.g.
    "planarize"), called with the rest; for drivers that take the problem's name as data."""
    if not isinstance(problem, str) or problem not in _FUNCTIONS:
        names = ", ".join(sorted(_FUNCTIONS))
        raise ValueError(f"problem: no problem named {problem!r} (the problems: {names})")
    return _FUNCTIONS[problem](*args, **kwargs)


_FUNCTIONS: Dict[str, Callable[..., Any]] = {}
