/*
 * provenance.h - how an output was made (hosted; issue 23 item 6).
 *
 * The program records its command line once (main); every curve CSV then
 * carries `# command:` and `# version:` lines, every --json object a
 * "provenance" member and every FITS file HISTORY cards, so a file found
 * on a disk a year later says what made it: the full command (scene with
 * its --set overrides, sensor, lens, normalisation and detector are all
 * on it), the version and the git revision of the build.
 */
#ifndef STRAY_PROVENANCE_H
#define STRAY_PROVENANCE_H

#define STRAY_VERSION "0.2.0"

/* Record the command line (shell-quoted where needed); safe to call once
 * per process, before any output is written. */
void stray_provenance_set(int argc, char **argv);

/* Record a command line already written out (a library caller saving
 * an output of an earlier call: that call's command); NULL is "". */
void stray_provenance_set_text(const char *command);

/* The recorded command line, or "" when none was recorded (a library
 * caller that did not say). */
const char *stray_provenance_command(void);

/* "0.2.0 (git <revision>)": the version and the build's git revision. */
const char *stray_provenance_version(void);

#endif /* STRAY_PROVENANCE_H */
