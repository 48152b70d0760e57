"""docs/embedding.md shows every example of examples/embedding/ as it is: each file given here
is the content of one of the document's fenced code blocks, line for line, and every block the
document marks with a file name ("<!-- example: NAME -->" on the line before) is that file.

    doc_examples.py DOC EXAMPLE [EXAMPLE...]
"""

import pathlib
import re
import sys

BLOCK = re.compile(r"<!-- example: (\S+) -->\n```[a-z+]*\n(.*?)```\n", re.S)


def main():
    doc = pathlib.Path(sys.argv[1])
    blocks = {name: text for name, text in BLOCK.findall(doc.read_text())}
    failed = False
    for path in map(pathlib.Path, sys.argv[2:]):
        text = path.read_text()
        if path.name not in blocks:
            print(f"{doc}: no block of {path.name}")
            failed = True
        elif blocks.pop(path.name) != text:
            print(f"{doc}: the block of {path.name} differs from {path}")
            failed = True
        else:
            print(f"{path.name}: {len(text.splitlines())} lines, as in {doc.name}")
    for name in blocks:
        print(f"{doc}: a block of {name}, which is no example given")
        failed = True
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
