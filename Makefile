# The two commands a newcomer needs:  `make course`  and  `make test`.
# Both create the virtual environment in $(VENV) on first use and install urkin into it.

PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.urkin-installed
# JupyterLab refuses to run as root unless told; containers often run as root
JUPYTER_FLAGS := $(if $(filter 0,$(shell id -u 2>/dev/null)),--allow-root,)
# Two pytest workers (pytest-xdist), as many as the 2-core machine the budgets are set on has;
# nbval's cells stay with their notebook's worker (--dist loadscope), in order, in one kernel.
NBVAL := $(PY) -m pytest -o addopts="" -p no:cacheprovider --nbval-current-env \
         --nbval-sanitize-with tests/nbval_sanitize.cfg -n 2 --dist loadscope

.PHONY: course test lint unit notebooks docs lessons grade-demo bench clean

$(STAMP): pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(0 if sys.version_info >= (3, 10) else "urkin needs Python 3.10 or newer; found " + sys.version.split()[0])'
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[dev,docs]"
	$(PY) -m ipykernel install --sys-prefix --name python3 --display-name "Python 3 (ipykernel)" > /dev/null
	@touch $(STAMP)

## make course: open the course notebooks in JupyterLab
course: $(STAMP)
	$(VENV)/bin/jupyter lab $(JUPYTER_FLAGS) course/

## make test: every check CI runs (lint, unit tests and doctests, autograder, notebooks, docs)
test: lint unit notebooks docs

lint: $(STAMP)
	$(PY) -m ruff check .
	$(PY) -m ruff format --check urkin tests bench docs/conf.py docs/check_offline.py

unit: $(STAMP)
	$(PY) -m pytest -n 2

# The stored outputs of solutions/ must not depend on the CPU: nbval compares them once as
# they come, and once more with another OpenBLAS kernel, numpy's baseline (SSE) loops instead
# of its AVX2/AVX-512 ones, and a single BLAS thread.
OTHER_CPU := OPENBLAS_CORETYPE=Sandybridge OPENBLAS_NUM_THREADS=1 \
             NPY_DISABLE_CPU_FEATURES="X86_V3 X86_V4 AVX512_SKX AVX512_ICL AVX512_SPR AVX2 FMA3"

notebooks: $(STAMP)
	$(PY) -m urkin course check
	$(NBVAL) --nbval solutions
	$(OTHER_CPU) $(NBVAL) --nbval solutions

# The student notebooks run top to bottom once, while the docs are built (urkin course render)
docs: $(STAMP)
	rm -rf docs/_build
	$(PY) -m sphinx -W --keep-going -q -b html docs docs/_build/html
	$(PY) docs/check_offline.py docs/_build/html
	@echo "docs: open docs/_build/html/index.html"

## make lessons: after editing solutions/*.py, re-execute the solution notebooks and rebuild course/
lessons: $(STAMP)
	$(PY) -m urkin course execute
	$(PY) -m urkin course build

bench: $(STAMP)
	$(PY) bench/kinematics.py
	$(PY) bench/ik.py
	$(PY) bench/ik_success.py
	$(PY) bench/ik_analytic.py
	$(PY) bench/grading.py
	$(PY) bench/planning.py
	$(PY) bench/planning.py --set mbm --problems 10 --runs 1
	$(PY) bench/tasks.py

clean:
	rm -rf docs/_build docs/lessons build *.egg-info
