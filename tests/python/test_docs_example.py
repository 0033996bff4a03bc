"""docs/python.md's example runs as written (from the checkout), and the README's two lines are
the ones that make the module importable."""
import contextlib
import io
import os
import re
import subprocess
import sys
import unittest

import module_support as ms


def block(path, language):
    with open(os.path.join(ms.SOURCE, path)) as f:
        found = re.findall(r"```" + language + r"\n(.*?)```", f.read(), re.S)
    assert found, f"{path}: no {language} block"
    return found


class DocsExample(unittest.TestCase):
    def test_the_example_runs(self):
        code = block("docs/python.md", "python")[0]
        out = io.StringIO()
        cwd = os.getcwd()
        os.chdir(ms.SOURCE)
        try:
            with contextlib.redirect_stdout(out):
                exec(compile(code, "docs/python.md", "exec"), {"__name__": "docs_example"})
        finally:
            os.chdir(cwd)
        lines = out.getvalue().splitlines()
        self.assertEqual(lines[0], "(12, 64, 64, 3) float32")
        self.assertIn("(6, 32, 48, 3)", lines)
        # The comment on the error line is the error the module raised.
        said = re.search(r"print\(e\)\s+# (.*)", code).group(1)
        self.assertEqual(lines[-1], said)

    def test_the_readme_lines_make_it_importable(self):
        # The README's two lines, run as written from the folder holding build/ (with Debian's
        # python3 first on the PATH, as on a fresh machine).
        readme = "\n".join(block("README.md", "sh")).splitlines()
        lines = [l for l in readme if l.startswith("export PYTHONPATH=") or "import slowlight" in l][:2]
        self.assertEqual(len(lines), 2, lines)
        build = os.path.dirname(os.environ["PYTHONPATH"].split(os.pathsep)[0])
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        env["PATH"] = "/usr/bin:/bin"
        p = subprocess.run(["/bin/sh", "-c", "\n".join(l.split("  #")[0] for l in lines)],
                           cwd=os.path.dirname(build), env=env, capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(p.stdout.strip(), "(12, 64, 64, 3)")


if __name__ == "__main__":
    ms.main()
