"""Which packages the wheel holds; everything else is in pyproject.toml.

The repository keeps the physics in ``model/`` and the optimisation and command line in
``planner/`` at the top level (the project's layout), and they install as ``liftplan.model``
and ``liftplan.planner`` (``liftplan`` is a namespace package: there is no ``liftplan/``
folder). pyproject.toml alone cannot say that: its ``packages.find`` names what it finds
after the folders (``model.water``), and a prefix cannot be added, so the list would have
to be written by hand (and was: a sub-package left out of it installed fine editable and
broke the wheel). Here ``find_packages`` lists every package under the two folders,
sub-packages added later included, and ``package_dir`` maps the two prefixes; setuptools
places each sub-package by the longest mapped prefix (``liftplan.model.water`` ->
``model/water``). Non-Python files in those folders (``py.typed``, data) come in through
MANIFEST.in (``include_package_data`` is on by default with pyproject.toml).
"""

from setuptools import find_packages, setup

FOLDERS = ("model", "planner")
FOUND = find_packages(include=[*FOLDERS, *(f"{folder}.*" for folder in FOLDERS)])

setup(
    package_dir={f"liftplan.{folder}": folder for folder in FOLDERS},
    packages=[f"liftplan.{name}" for name in FOUND],
)
