"""`python3 -c "import filum"` (the README's check) works in any Python 3 of the module's version:
loading the module must not need numpy, which an interpreter other than Debian's (pyenv, a
virtualenv) may lack. Arrays need it when they are made, not before."""
import subprocess
import sys


def test_importing_the_module_does_not_import_numpy():
    code = "import sys, filum; assert 'numpy' not in sys.modules, 'import filum imported numpy'; print(filum.Scene)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "filum.Scene" in done.stdout
