/* Shared by the camera path sources (not installed). */
#ifndef PNPR_CAMERA_PATH_INTERNAL_H
#define PNPR_CAMERA_PATH_INTERNAL_H

#include <pointnpr/camera_path.h>

#include <stdio.h>

/* What is wrong with one key on its own (times aside): 0 nothing, 1 a bad value, 2 a non-finite
 * one; why receives the reason. */
int pnpr_camera_key_problem(const pnpr_camera_key *key, char *why, size_t size);
/* At least 3 keys and the last repeats the first key's eye, target and up exactly. */
int pnpr_camera_path_loop_closed(const pnpr_camera_path *path);

#endif
