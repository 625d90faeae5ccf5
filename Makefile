# refracta: `make demo` and `make test` are the two set-up commands (README).
PYTHON ?= python3
PYTEST_ARGS ?=
SOURCES := $(shell find cpp python -name '*.h' -o -name '*.cpp' 2>/dev/null) CMakeLists.txt pyproject.toml

.PHONY: install demo test lint tidy bench stubs docs clean
install: .install.stamp

# Debian packages first, then the package itself (editable) into the current Python.
.install.stamp: .ci/debian-packages.txt $(SOURCES)
	bash .ci/install-debian-packages
	$(PYTHON) -m pip install --upgrade --quiet pip
	# Build requirements installed once, then no build isolation: the build directory keeps the
	# same compiler paths, so rebuilding after an edit is incremental.
	$(PYTHON) -m pip install --quiet 'scikit-build-core>=0.9' 'pybind11>=2.12'
	$(PYTHON) -m pip install --no-build-isolation -e '.[test]'
	touch $@

demo: install
	$(PYTHON) -m refracta demo --out out

# The suite, the notebooks, then the static checks (`make lint`); any failing fails `make test`
# (and so CI), after all have run, and the last line names what failed. The notebooks run apart,
# bounded in time and once more if they fail: on 4 December 2 runs in ~12 stalled with kernel and
# client both idle, waiting on each other's ZMQ messages (a Jupyter hang, seen in the fresh-clone run
# and standalone; the notebooks themselves take ~20 s). A notebook that really fails fails twice.
NOTEBOOKS = timeout 300 $(PYTHON) -m pytest --nbmake --nbmake-timeout=120 notebooks
test: install
	@failed=""; \
	$(PYTHON) -m pytest --durations=25 tests $(PYTEST_ARGS) || failed="$$failed pytest"; \
	$(NOTEBOOKS) || { echo "make test: the notebooks failed or stalled; running them once more"; $(NOTEBOOKS); } \
		|| failed="$$failed notebooks"; \
	$(MAKE) --no-print-directory lint || failed="$$failed lint"; \
	if [ -n "$$failed" ]; then echo "make test: FAILED:$$failed"; exit 1; fi

# Static checks, each run even when one before it fails (configurations in pyproject.toml,
# .ci/vulture_whitelist.py and .clang-tidy). C++ warnings are errors in the build itself
# (CMakeLists.txt, REFRACTA_WERROR), so `install` has already checked them. clang-tidy checks
# each C++ layer as one TU (.ci/clang_tidy.py says why): 1-2 min on 2 cores, not 4-9.
LINT_PYTHON := python tests benchmarks
lint: install
	@failed=""; \
	echo "== ruff check"; $(PYTHON) -m ruff check $(LINT_PYTHON) || failed="$$failed ruff-check"; \
	echo "== ruff format --check"; $(PYTHON) -m ruff format --check $(LINT_PYTHON) || failed="$$failed ruff-format"; \
	echo "== mypy"; $(PYTHON) -m mypy || failed="$$failed mypy"; \
	echo "== vulture (dead code)"; $(PYTHON) -m vulture || failed="$$failed vulture"; \
	echo "== clang-tidy (C++)"; $(PYTHON) .ci/clang_tidy.py || failed="$$failed clang-tidy"; \
	if [ -n "$$failed" ]; then echo "make lint: FAILED:$$failed"; exit 1; fi

# clang-tidy alone (also part of `make lint`); `make tidy TIDY_ARGS=--per-tu` checks TU by TU.
TIDY_ARGS ?=
tidy: install
	$(PYTHON) .ci/clang_tidy.py $(TIDY_ARGS)

bench: install
	bash .ci/install-debian-packages .ci/bench-packages.txt
	$(PYTHON) benchmarks/run_all.py

# Regenerates python/refracta/_core.pyi from the built module (tests/python/test_stubs.py checks it).
stubs: install
	REFRACTA_UNWRAPPED_CORE=1 $(PYTHON) -m pybind11_stubgen refracta._core -o build/stubs
	cp build/stubs/refracta/_core.pyi python/refracta/_core.pyi

# Regenerates cpp/generated/docstrings.h, the bindings' docstrings, from the C++ headers' comments
# (pybind11_mkdoc + libclang; tests/package/test_docstrings.py checks it). The build reads the file.
docstrings:
	$(PYTHON) .ci/docstrings.py

# API reference (autodoc + napoleon) and the notebooks (myst-nb, not executed) into build/docs;
# -W: a warning fails the build, as in tests/package/test_docs.py.
docs: install
	$(PYTHON) -m sphinx -W --keep-going -b html python/docs build/docs

clean:
	rm -rf build out .install.stamp
