# review: `stray review`'s engine (issue 25, docs/review.md): the project
# file, the plan of steps (each a `stray` command line), the runner with
# its manifest and --resume, review.json, the section drawing and the
# report.  Public header review/include/review/review.h; the command
# itself is tools/cmd_review.c.  Listed in MODULES after tools.

REVIEW_SRC := $(wildcard review/*.c)
REVIEW_OBJ := $(REVIEW_SRC:%.c=$(B)/obj/%.o)
REVIEW_LIB := $(B)/lib/libreview.a
REVIEW_CFLAGS := -Ireview/include -D_DEFAULT_SOURCE -I/usr/include/cjson \
	-I/usr/include/plplot

$(REVIEW_OBJ): EXTRA_CFLAGS += $(REVIEW_CFLAGS) -Ireview
$(REVIEW_LIB): $(REVIEW_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

all: $(REVIEW_LIB)

$(B)/obj/tools/cmd_review.o: EXTRA_CFLAGS += -Ireview/include
$(STRAY_BIN): $(REVIEW_LIB)
TOOLS_LDLIBS := $(REVIEW_LIB) $(STRAY_LIB) $(TOOLS_LDLIBS)
