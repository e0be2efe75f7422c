"""The hand-written type stubs declare every public name of the module and of stairplan.optim."""
import os
import re

import stairplan


def declared(stub):
    with open(os.path.join(os.path.dirname(stairplan.__file__), stub)) as f:
        text = f.read()
    return text


def test_stubs_cover_the_public_names():
    for module, stub in ((stairplan, "__init__.pyi"), (stairplan.optim, "optim.pyi")):
        text = declared(stub)
        public = [n for n in dir(module) if not n.startswith("_") and n not in ("annotations",)]
        missing = [n for n in public
                   if not re.search(rf"^(class {n}\b|def {n}\(|{n}: |from \. import {n} as {n}$)", text, re.M)]
        assert not missing, f"{stub} lacks {missing}"
    assert "Plans, and validates" in stairplan.plan.__doc__
