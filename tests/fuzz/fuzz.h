/* SPDX-License-Identifier: MIT */
/* fuzz.h: what the fuzz targets share (docs/design.md §8): libFuzzer's entry
 * point, linked either with libFuzzer (make fuzz, clang) or with replay.c
 * (make check, the normal compiler), and a private file the input is
 * written to, since the readers under test take paths. */
#ifndef ARVO_FUZZ_H
#define ARVO_FUZZ_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Writes data to NAME in a private temporary directory (made on first use,
 * removed at exit) and returns the file's path. */
const char *fuzz_file(const char *name, const uint8_t *data, size_t size);

#endif
