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

# The suite, then the static checks (`make lint`); either failing fails `make test` (and so CI),
# after both have run.
test: install
	@status=0; \
	$(PYTHON) -m pytest --nbmake tests notebooks $(PYTEST_ARGS) || status=1; \
	$(MAKE) --no-print-directory lint || status=1; \
	exit $$status

# Static checks, each run even when one before it fails (configurations in pyproject.toml and
# .ci/vulture_whitelist.py). C++ warnings are errors in the build itself (CMakeLists.txt,
# REFRACTA_WERROR), so `install` has already checked them.
LINT_PYTHON := python tests benchmarks
lint: install
	@status=0; \
	echo "== ruff check"; $(PYTHON) -m ruff check $(LINT_PYTHON) || status=1; \
	echo "== ruff format --check"; $(PYTHON) -m ruff format --check $(LINT_PYTHON) || status=1; \
	echo "== mypy"; $(PYTHON) -m mypy || status=1; \
	echo "== vulture (dead code)"; $(PYTHON) -m vulture || status=1; \
	exit $$status

# clang-tidy (.clang-tidy) on the library's C++: run it before committing C++ changes. Not part of
# `make test`: on a fresh clone it took 228 s of the 20.5 minutes `make test` then took with it
# (set-up ~5 min, pytest 11 min, the rest of lint 1.5 min), over CI's 20-minute budget.
tidy: install
	bash .ci/clang-tidy

bench: install
	$(PYTHON) benchmarks/run_all.py

# Regenerates python/refracta/_core.pyi from the built module (tests/python/test_stubs.py checks it).
stubs: install
	$(PYTHON) -m pybind11_stubgen refracta._core -o build/stubs
	cp build/stubs/refracta/_core.pyi python/refracta/_core.pyi

# API reference (autodoc + napoleon) and the notebooks (myst-nb, not executed) into build/docs;
# -W: a warning fails the build, as in tests/package/test_docs.py.
docs: install
	$(PYTHON) -m sphinx -W --keep-going -b html python/docs build/docs

clean:
	rm -rf build out .install.stamp
