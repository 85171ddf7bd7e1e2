#!/usr/bin/python3
"""The rigid piston solid (cosim.rigid_piston) as a script: `rigid_piston.py SCENE --out DIR --coupler EP ...`.

The cosim package beside this file is imported (python/cosim, <build>/python/cosim); `--help` lists the options.
"""
import sys

from cosim.rigid_piston import main

if __name__ == "__main__":
    sys.exit(main())
