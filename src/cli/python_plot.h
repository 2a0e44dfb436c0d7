// `erpt compare`'s plot, drawn by the Python package (python/erpt/plot.py, matplotlib): the CLI
// runs `python3 -m erpt.plot` on the report it wrote.
#pragma once

#include <string>

namespace erpt::cli {

// Draws the convergence plot of compare.json `report` to `image`. Empty on success; otherwise
// why not and the command that would draw it. The interpreter: $ERPT_PYTHON, else Debian's
// /usr/bin/python3, else python3 on the PATH; the package is found beside the erpt binary
// (build/python) or where scripts/install-python.sh put it.
std::string plotComparison(const std::string& report, const std::string& image);

}  // namespace erpt::cli
