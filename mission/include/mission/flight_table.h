/*
 * flight_table.h - a flight table (stray firmware-table --out-bin) read
 * from a file for the commands that fly the flight module (stray orbit,
 * stray availability).
 */
#ifndef STRAY_MISSION_FLIGHT_TABLE_H
#define STRAY_MISSION_FLIGHT_TABLE_H

#include "fdrfw/fdrfw.h"
#include "stray/error.h"

/* Read path into t and check it (size, magic, CRC, ranges): STRAY_OK, or
 * an error naming the file. */
int flight_table_load(const char *path, struct fdrfw_table *t,
		      struct stray_error *err);

#endif /* STRAY_MISSION_FLIGHT_TABLE_H */
