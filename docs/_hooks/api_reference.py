"""mkdocs hook: let mkdocstrings (griffe) read ``liftplan.model`` and ``liftplan.planner``.

The repository keeps the packages in ``model/`` and ``planner/`` at its root; setup.py's
``package_dir`` installs them as ``liftplan.model`` and ``liftplan.planner``
(``liftplan`` itself is a namespace package with no folder). griffe finds packages by their
folder names, so on every build this hook links the mapped folders into a temporary
``liftplan/`` tree and puts it first on the python handler's search paths. The mapping is read
from setup.py, so the docs follow the packaging.

The packages export their public names lazily (PEP 562: a ``_EXPORTS`` dict of public name ->
submodule, read by ``__getattr__``), which static analysis cannot see. :class:`LazyExports`,
a griffe extension (mkdocs.yml names it in the handler's ``extensions``), reads that dict from
the source and adds each name to its package as an alias of its definition, so the reference
pages name only the package-level public API (``liftplan.model.solve``), never the submodule
that happens to define it.

Images the docs show from ``studies/out/`` (written by the studies, outside ``docs/``) are
linked as ``../studies/out/NAME.png`` (a path that also works on GitHub) and added to the site
under ``studies/out/``.
"""

from __future__ import annotations

import ast
import atexit
import re
import shutil
import tempfile
from pathlib import Path

import griffe
from mkdocs.plugins import event_priority
from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parents[2]
STUDIES_OUT = "studies/out"
IMAGE_LINK = re.compile(r"\]\(\.\./" + re.escape(STUDIES_OUT) + r"/")
# reStructuredText in the docstrings that Markdown would show raw: roles, and "Example::"
ROLE = re.compile(r":(?:func|class|mod|meth|attr|data|exc|obj):`~?([^`]+)`")
LITERAL_INTRO = re.compile(r"::$", re.MULTILINE)


def _package_tree():
    """A temporary folder holding ``liftplan/<sub>`` links to the folders setup.py maps
    (``FOLDERS``: ``model/`` is ``liftplan.model``, ``planner/`` is ``liftplan.planner``)."""
    folders = ast.literal_eval(re.search(r"^FOLDERS = (.+)$", (ROOT / "setup.py").read_text(), re.M)[1])
    mapping = {f"liftplan.{folder}": folder for folder in folders}
    tree = Path(tempfile.mkdtemp(prefix="liftplan-docs-"))
    atexit.register(shutil.rmtree, tree, ignore_errors=True)
    for package, folder in mapping.items():
        top, _, sub = package.partition(".")
        if sub and "." not in sub:  # liftplan.model -> model/ (sub-packages come with it)
            (tree / top).mkdir(exist_ok=True)
            (tree / top / sub).symlink_to(ROOT / folder, target_is_directory=True)
    return tree


@event_priority(100)  # before mkdocstrings' on_config, which makes the handler
def on_config(config):
    handler = config.plugins["mkdocstrings"].config.handlers.setdefault("python", {})
    handler["paths"] = [str(_package_tree()), *handler.get("paths", [])]
    return config


def on_files(files, config):
    for image in sorted((ROOT / STUDIES_OUT).glob("*.png")):
        files.append(
            File(
                f"{STUDIES_OUT}/{image.name}",
                src_dir=str(ROOT),
                dest_dir=config.site_dir,
                use_directory_urls=config.use_directory_urls,
            )
        )
    return files


def on_page_markdown(markdown, page, config, files):
    # ../studies/out/x.png from docs/page.md on GitHub is studies/out/x.png on the site
    depth = page.file.src_uri.count("/")
    return IMAGE_LINK.sub("](" + "../" * depth + STUDIES_OUT + "/", markdown)


def _exports(module):
    """The ``_EXPORTS`` dict of a lazily exporting package's ``__init__``, or None."""
    if not isinstance(module.filepath, Path) or module.filepath.name != "__init__.py":
        return None  # a namespace package (a list of folders) or a plain module
    tree = ast.parse(Path(module.filepath).read_text(encoding="utf-8"))
    for node in tree.body:
        target = node.target if isinstance(node, ast.AnnAssign) else getattr(node, "targets", [None])[0]
        if isinstance(target, ast.Name) and target.id == "_EXPORTS" and node.value is not None:
            # a literal dict built with dict.fromkeys: evaluated with nothing else in reach
            code = compile(ast.Expression(node.value), str(module.filepath), "eval")
            return eval(code, {"__builtins__": {}, "dict": dict})  # noqa: S307
    return None


class LazyExports(griffe.Extension):
    """Add a lazily exporting package's public names to it, as aliases of their definitions;
    show the docstrings' reStructuredText roles (``:func:`x```) as code and their literal
    block openers (``Example::``) as a colon (the indented block is code either way)."""

    def on_instance(self, *, obj, **kwargs):
        if obj.docstring is not None:
            text = ROLE.sub(r"`\1`", obj.docstring.value)
            obj.docstring.value = LITERAL_INTRO.sub(":", text)

    def on_package(self, *, pkg, **kwargs):
        self._walk(pkg)

    def _walk(self, module):
        for member in list(module.modules.values()):
            self._walk(member)
        # the public names (``__version__`` is metadata, read at run time: not an API name)
        exports = {name: sub for name, sub in (_exports(module) or {}).items() if not name.startswith("__")}
        if exports:
            # every definition first: a name may be its own submodule's (``solve``, ``plan``),
            # and the alias then takes the submodule's place in the package
            targets = {name: self._definition(module, sub, name) for name, sub in exports.items()}
            for name, target in targets.items():
                module.set_member(name, griffe.Alias(name, target, parent=module))
            module.exports = sorted(exports)

    @staticmethod
    def _definition(module, submodule, name):
        for part in submodule.split("."):
            module = module.modules[part]
        return module.members[name]
