"""Shared by the perf/ report scripts: where the repository is, the environment for mpirun as
root, and writing a generated table between <!-- NAME:begin --> and <!-- NAME:end -->."""
import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT='1', OMPI_ALLOW_RUN_AS_ROOT_CONFIRM='1')


def replace_section(path, name, text, heading=None):
    """Puts text between the markers of `name` in the file (appending the markers under
    `heading` when the file has none yet)."""
    s = open(path).read()
    begin, end = '<!-- %s:begin -->' % name, '<!-- %s:end -->' % name
    if begin not in s:
        s += '\n%s\n%s\n%s\n' % (heading or '', begin, end)
    s = re.sub(r'(%s\n).*?(%s)' % (re.escape(begin), re.escape(end)), lambda m: m[1] + text + '\n' + m[2], s, flags=re.S)
    open(path, 'w').write(s)
