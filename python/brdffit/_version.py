# SPDX-License-Identifier: MIT
"""The package's version, and the library version it was written for."""

# The package follows the library it wraps: the same version.  The library
# must have the same major and minor version (and the struct layouts that
# brdffit/_abi.py mirrors, checked at load time); any patch level is accepted.
__version__ = "1.0.0"
LIBRARY_VERSION = (1, 0)
