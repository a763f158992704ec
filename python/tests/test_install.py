"""`cmake --install`: the command line lands in <prefix>/bin and the module where a python3 whose
prefix is <prefix> imports it without PYTHONPATH (CMakeLists.txt's install rules,
cmake/python_site_dir.py). Installs the build that TRIPATH_BINARY belongs to into a temporary
prefix and imports it from a venv made there."""
import os
import pathlib
import subprocess
import sys

TRIPATH = os.environ.get("TRIPATH_BINARY", "")
SITE_DIR = pathlib.Path(__file__).resolve().parents[2] / "cmake" / "python_site_dir.py"


def site_dir(prefix):
    return subprocess.run([sys.executable, str(SITE_DIR), str(prefix)], check=True, capture_output=True,
                          text=True).stdout.strip()


def test_the_module_goes_where_this_python_looks_or_under_the_prefix(tmp_path):
    # Under this interpreter's own prefix: a folder it searches. Under another: the standard one.
    assert site_dir(sys.prefix) in [os.path.abspath(p) for p in sys.path]
    version = "python%d.%d" % sys.version_info[:2]
    assert site_dir(tmp_path) == str(tmp_path / "lib" / version / "site-packages")


def test_installed_module_imports_without_pythonpath(tmp_path):
    build = pathlib.Path(TRIPATH).parent
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", "--system-site-packages", str(tmp_path)],
                   check=True)
    subprocess.run(["cmake", "--install", str(build), "--prefix", str(tmp_path)], check=True, capture_output=True)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    imported = subprocess.run([str(tmp_path / "bin" / "python3"), "-c", "import tripath; print(tripath.__file__)"],
                              env=env, cwd=tmp_path, check=True, capture_output=True, text=True).stdout.strip()
    assert imported.startswith(site_dir(tmp_path) + os.sep), imported
    scenes = subprocess.run([str(tmp_path / "bin" / "tripath"), "scenes"], env=env, check=True, capture_output=True,
                            text=True).stdout
    assert scenes.startswith("cornell ")
