"""The folder under an install prefix where `cmake --install` puts the Python module: the first of
the folders that Python keeps its packages in under that prefix which this interpreter searches
(for Debian's /usr/bin/python3 and the prefix /usr/local: /usr/local/lib/python3.X/dist-packages),
else the one that any python3 whose prefix it is searches, a venv made there included
(<prefix>/lib/python3.X/site-packages).

    python3 cmake/python_site_dir.py PREFIX
"""
import os
import sys

prefix = os.path.abspath(sys.argv[1])
version = "python%d.%d" % sys.version_info[:2]
candidates = [os.path.join(prefix, "lib", version, "site-packages"),
              os.path.join(prefix, "lib", version, "dist-packages"),
              os.path.join(prefix, "lib", "python3", "dist-packages"),
              os.path.join(prefix, "local", "lib", version, "dist-packages")]
searched = {os.path.abspath(p) for p in sys.path if p}
print(next((c for c in candidates if c in searched), candidates[0]))
