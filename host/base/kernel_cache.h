// SPDX-License-Identifier: Apache-2.0
/* kernel_cache.h - the on-disk cache of compiled device code (OpenCL
 * program binaries, Vulkan pipeline caches), shared by the device backends.
 *
 * A first frame on a device spends most of its time compiling kernels; the
 * result depends only on the kernel source, the build options, the device
 * and its driver, and this library's version, so it is kept on disk under a
 * key made of all of them and loaded by the next run.
 *
 * The folder: $RTCL_CACHE_DIR, else $XDG_CACHE_HOME/rtcl (an absolute
 * XDG_CACHE_HOME only, as the XDG spec says), else $HOME/.cache/rtcl;
 * created (mode 0700) when missing. RTCL_CACHE_DIR=off (or 0, none, "")
 * turns the cache off. A folder that cannot be made or written is not an
 * error: the run compiles as without a cache and says nothing.
 *
 * An entry is one file KIND-HASH.bin (KIND "cl" or "vk", HASH 16 hex digits
 * of the key), written atomically (base/atomic_file.h: a temporary in the
 * same folder, renamed over the entry), holding a 48-byte header (a magic,
 * the key's two hashes and length, the payload's size and FNV-1a checksum)
 * and the payload. A file whose header or checksum does not match is
 * deleted and reported as a miss, so a truncated or overwritten entry never
 * reaches a driver. Nothing evicts entries: each scene's specialisation is
 * one entry of a few MB at most; deleting the folder is always safe. */
#ifndef RT_KERNEL_CACHE_H
#define RT_KERNEL_CACHE_H

#include <stddef.h>
#include <stdint.h>

/* A key being hashed: two 64-bit FNV-1a lanes (different offset bases, the
 * second over the bytes complemented) and the bytes hashed. */
typedef struct rt_kc_key {
    uint64_t a, b, len;
} rt_kc_key;

/* An empty key. */
void rt_kc_key_init(rt_kc_key *k);

/* Adds one field of n bytes: its length first, so that fields are
 * delimited ("ab" + "c" is not "a" + "bc"). */
void rt_kc_key_add(rt_kc_key *k, const void *data, size_t n);

/* rt_kc_key_add of a NUL-terminated string (NULL: ""). */
void rt_kc_key_add_str(rt_kc_key *k, const char *s);

/* The cache folder into dir (cap bytes), created when missing. 1 when the
 * cache is on and the folder is writable; 0 when it is off or unusable
 * (dir is then ""). Looked up anew each call (the environment may change). */
int rt_kc_folder(char *dir, size_t cap);

/* The payload of entry KIND for key in dir, as a new buffer (free()) of
 * *size bytes; NULL when there is none or it is damaged (then the file is
 * deleted). */
void *rt_kc_load(const char *dir, const char *kind, const rt_kc_key *key, size_t *size);

/* Writes the entry atomically; failures are silent (the cache is an
 * optimisation). */
void rt_kc_save(const char *dir, const char *kind, const rt_kc_key *key, const void *data,
                size_t size);

/* Deletes the entry (a payload the driver refused). */
void rt_kc_remove(const char *dir, const char *kind, const rt_kc_key *key);

#endif /* RT_KERNEL_CACHE_H */
