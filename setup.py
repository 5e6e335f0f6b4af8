"""Ships `src/aiobt` as `aiobt` and the `services/` folder as `aiobt_services`."""

from setuptools import find_packages, setup

ROOTS = {"aiobt": "src/aiobt", "aiobt_services": "services"}

setup(
    packages=[
        name
        for root, folder in ROOTS.items()
        for name in [root, *(f"{root}.{sub}" for sub in find_packages(folder))]
    ],
    package_dir=ROOTS,
)
