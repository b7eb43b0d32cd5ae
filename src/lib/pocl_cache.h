/* SPDX-License-Identifier: MIT */
/* pocl_cache.h -- the directory PoCL keeps compiled kernels in: chosen (or
 * checked) once per process, before the library's first OpenCL call. */
#ifndef BRDFFIT_POCL_CACHE_H
#define BRDFFIT_POCL_CACHE_H

#include "internal.h"

/* Decide PoCL's kernel cache directory, once per process (thread-safe; later
 * calls return the first call's answer).  The directory, whichever it is,
 * must be private (bf_private_dir):
 *   POCL_CACHE_DIR set: that directory, or BRDFFIT_E_CACHE_DIR saying why
 *   not and what to do (the variable is left as it is).
 *   Unset: the first private directory among $XDG_CACHE_HOME/brdffit/pocl,
 *   $HOME/.cache/brdffit/pocl and ${TMPDIR:-/tmp}/brdffit-pocl-UID;
 *   POCL_CACHE_DIR is then set to it (the library's only setenv), or
 *   BRDFFIT_E_CACHE_DIR lists every directory tried and why it was refused.
 * When refused, the OpenCL platform must not be touched (PoCL would fall
 * back to a shared directory of its own). */
brdffit_status bf_pocl_cache_ready(brdffit_error *err);

/* 0 when dir is a private directory, else -1 with the reason in why ("is a
 * symbolic link", ...).  Private: owned by this user, a directory, not a
 * symbolic link, not group- or world-writable, a file can be made in it,
 * and every directory above it (and, above a symbolic link, above where it
 * leads) owned by root or this user and, when others may write to it,
 * sticky.  What is missing is made with mode 0700, walking down from the
 * root, only below directories that passed: nothing is created in or under
 * one that fails. */
int bf_private_dir(const char *dir, char *why, size_t len);

#endif /* BRDFFIT_POCL_CACHE_H */
