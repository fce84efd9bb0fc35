"""Shared by the perf/ report scripts: where the repository is, the environment for mpirun as
root, and writing a generated table between <!-- NAME:begin --> and <!-- NAME:end -->."""
import os
import re
import textwrap

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT='1', OMPI_ALLOW_RUN_AS_ROOT_CONFIRM='1')
LINE_START = re.compile(r'([-+*>#]|\d+[.)])(\s|$)')


def wrap_prose(text, width=100):
    """Wraps the prose lines of generated Markdown at `width` columns; table rows, images,
    headings, markers and indented lines are left as they are."""
    out = []
    for line in text.split('\n'):
        if len(line) <= width or line.startswith(('|', '!', '#', '<', ' ')):
            out.append(line)
        else:
            wrapped = textwrap.wrap(line, width, break_long_words=False, break_on_hyphens=False)
            out.append(wrapped[0])
            for w in wrapped[1:]:  # a continuation must not read as a list item or heading
                if LINE_START.match(w):
                    out[-1] += ' ' + w
                else:
                    out.append(w)
    return '\n'.join(out)


def replace_section(path, name, text, heading=None):
    """Puts text, its prose wrapped, between the markers of `name` in the file (appending the
    markers under `heading` when the file has none yet)."""
    text = wrap_prose(text)
    s = open(path).read()
    begin, end = '<!-- %s:begin -->' % name, '<!-- %s:end -->' % name
    if begin not in s:
        s += '\n%s\n%s\n%s\n' % (heading or '', begin, end)
    s = re.sub(r'(%s\n).*?(%s)' % (re.escape(begin), re.escape(end)), lambda m: m[1] + text + '\n' + m[2], s, flags=re.S)
    open(path, 'w').write(s)
