#!/usr/bin/env bash
# Prints the Python interpreter the module is built for and tested with: $ERPT_PYTHON, else
# Debian's /usr/bin/python3 (numpy, matplotlib and pytest come from its packages), else python3.
if [ -n "${ERPT_PYTHON:-}" ]; then echo "$ERPT_PYTHON"
elif [ -x /usr/bin/python3 ]; then echo /usr/bin/python3
else command -v python3; fi
