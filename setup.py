"""The one thing pyproject.toml cannot say: the packages found under camgen/ and linkgen/, plus the top-level
templates/ folder installed as the package ``camgen.examples`` (the bundled templates; the folder stays where users
of a checkout find it)."""
from setuptools import find_packages, setup

setup(packages=[*find_packages(include=["camgen*", "linkgen*"]), "camgen.examples"],
      package_dir={"camgen.examples": "templates"})
