/* SPDX-License-Identifier: Apache-2.0 */
/* video_out.h - 'rtcl animate -o out.mp4': frames piped into an ffmpeg child
 * process, which encodes the video. rtcl links no codec: ffmpeg (Debian's
 * ffmpeg package) is found on PATH at run time, and without it the caller
 * says how to write frames instead. */
#ifndef RTCL_VIDEO_OUT_H
#define RTCL_VIDEO_OUT_H

#include <stddef.h>

typedef struct cli_video cli_video;

/* 1 when path names a video by its extension (.mp4, .mkv, .webm, in any
 * case), else 0. */
int cli_is_video_path(const char *path);

/* 1 when an executable ffmpeg is on PATH. */
int cli_have_ffmpeg(void);

/* 1 when path could be written as a video (its folder exists and is
 * writable), checked before the frames are made; else 0 with the reason in
 * why. */
int cli_video_check(const char *path, char *why, size_t cap);

/* Starts ffmpeg writing path (replaced once the video is complete: ffmpeg
 * writes a temporary beside it, base/atomic_file.h) from width x height
 * RGB frames at fps: H.264 (libx264) in .mp4 and .mkv where this ffmpeg has
 * it, else MPEG-4 part 2; VP9 (else VP8) in .webm; 4:2:0 chroma, padded by a
 * black column or row to even sides when odd. path reaches ffmpeg as one
 * argument (no shell), as a file: URL, so that no path is taken for an
 * option or a protocol. Unless metadata is 1, the container holds no time
 * or random id (ffmpeg's bitexact mode), so equal frames give an equal
 * file. ffmpeg's messages are kept and shown only on failure. NULL on
 * failure with the reason in why. */
cli_video *cli_video_open(const char *path, int width, int height, double fps, int metadata,
                          char *why, size_t cap);

/* Sends one frame: width x height x 3 floats in rows from the top, clamped
 * to [0, 1] and rounded to 8 bits as the PPM writer does. 0 with the reason
 * in why when ffmpeg failed (it is then waited for; call cli_video_abort). */
int cli_video_write(cli_video *video, const float *rgb, char *why, size_t cap);

/* Ends the stream, waits for ffmpeg, puts the video in place and frees
 * video. 1 when the video was written; 0 with the reason (ffmpeg's own
 * messages included) in why, an existing file at the path untouched. */
int cli_video_close(cli_video *video, char *why, size_t cap);

/* Stops ffmpeg without finishing the video, removes its temporary and frees
 * video (NULL: nothing); an existing file at the path is untouched. */
void cli_video_abort(cli_video *video);

#endif /* RTCL_VIDEO_OUT_H */
