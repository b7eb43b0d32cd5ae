/* SPDX-License-Identifier: MIT */
/* pocl_cache.h -- the directory PoCL keeps compiled kernels in: chosen (or
 * checked) once per process, before the library's first OpenCL call. */
#ifndef BRDFFIT_POCL_CACHE_H
#define BRDFFIT_POCL_CACHE_H

#include "internal.h"

/* Decide PoCL's kernel cache directory, once per process (thread-safe; later
 * calls return the first call's answer).
 *   POCL_CACHE_DIR set: it must be a writable directory (made when missing).
 *   Unset: the first private directory among $XDG_CACHE_HOME/brdffit/pocl,
 *   $HOME/.cache/brdffit/pocl and ${TMPDIR:-/tmp}/brdffit-pocl-UID, made
 *   with mode 0700 or, when it exists, owned by this user, not a symbolic
 *   link, not group- or world-writable, in a parent others cannot replace it
 *   in; POCL_CACHE_DIR is then set to it (the library's only setenv).
 * BRDFFIT_OK, or BRDFFIT_E_CACHE_DIR with every directory tried and why it
 * was refused; the OpenCL platform must then not be touched (PoCL would fall
 * back to a shared directory of its own). */
brdffit_status bf_pocl_cache_ready(brdffit_error *err);

/* 0 when dir is a private directory as above (made when missing), else -1
 * with the reason in why ("is a symbolic link", ...). */
int bf_private_dir(const char *dir, char *why, size_t len);

#endif /* BRDFFIT_POCL_CACHE_H */
