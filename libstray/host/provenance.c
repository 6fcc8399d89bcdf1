/*
 * provenance.c - the command line and build of this process
 * (stray/provenance.h).
 */
#include <stdio.h>
#include <string.h>

#include "stray/provenance.h"

#ifndef STRAY_GIT_REV	/* set by libstray/module.mk from `git describe` */
#define STRAY_GIT_REV "unknown"
#endif

static char command[4096];

/* Characters a POSIX shell reads as themselves outside quotes. */
static int plain(const char *s)
{
	if (!*s)
		return 0;
	for (; *s; s++)
		if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
			    "0123456789_-+=.,:/@%^", *s))
			return 0;
	return 1;
}

void stray_provenance_set(int argc, char **argv)
{
	size_t len = 0;
	int i;

	command[0] = '\0';
	for (i = 0; i < argc && len + 4 < sizeof(command); i++) {
		const char *a = argv[i];

		if (i)
			command[len++] = ' ';
		if (plain(a)) {
			len += (size_t)snprintf(command + len,
						sizeof(command) - len, "%s", a);
			continue;
		}
		/* 'it'\''s': single quotes, each ' closed, escaped, reopened */
		command[len++] = '\'';
		for (; *a && len + 6 < sizeof(command); a++) {
			if (*a == '\'') {
				memcpy(command + len, "'\\''", 4);
				len += 4;
			} else if (*a == '\n' || *a == '\r') {
				command[len++] = ' ';	/* one line */
			} else {
				command[len++] = *a;
			}
		}
		command[len++] = '\'';
		command[len] = '\0';
	}
	if (len >= sizeof(command))
		len = sizeof(command) - 1;
	command[len] = '\0';
}

void stray_provenance_set_text(const char *text)
{
	snprintf(command, sizeof(command), "%s", text ? text : "");
}

const char *stray_provenance_command(void)
{
	return command;
}

const char *stray_provenance_version(void)
{
	return STRAY_VERSION " (git " STRAY_GIT_REV ")";
}
