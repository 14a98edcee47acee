/* output_check.c - whether a command may write a file of its own (a converged mission, an
 * FMU, a result file named on the command line): never the mission it reads or one of its
 * data files (compared by device and inode: any spelling of the path), never a folder, and
 * an existing file only when the caller says so (lv_mission.h, lv_output_check). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <string.h>
#include <sys/stat.h>

#include "core/status.h"
#include "lvsim/lv_mission.h"

lv_status lv_output_check(const char *path, const lv_mission *m, unsigned flags, lv_err *err)
{
    if (path == NULL || path[0] == '\0')
        return lv_fail(err, LV_ERR_INPUT, "the output file's name is empty");
    const size_t n = strlen(path);
    for (size_t i = 0; i < n; i++) /* the messages print it on one line */
        if ((unsigned char)path[i] < 0x20 || path[i] == 0x7f)
            return lv_fail(err, LV_ERR_INPUT, "the output file's name holds a control character "
                           "(byte %zu is 0x%02x): name another file", i + 1,
                           (unsigned)(unsigned char)path[i]);
    if (path[n - 1] == '/')
        return lv_fail(err, LV_ERR_INPUT, "'%s' names a folder: name the file to write", path);
    struct stat so;
    /* a symbolic link is the user's, dangling or not: never replaced by a file (the rename
     * that writes the output would replace the link itself); one to an input is named as
     * that input below */
    const int link = lstat(path, &so) == 0 && S_ISLNK(so.st_mode);
    static const char *const link_msg = "'%s' is a symbolic link: lvsim does not replace it, "
                                        "also with --force; name another file";
    if (stat(path, &so) != 0) {
        if (link)
            return lv_fail(err, LV_ERR_INPUT, link_msg, path);
        if (errno == ENOENT)
            return LV_OK; /* a missing folder on the way is the writer's error, with its name */
        char text[128];
        if (errno == ENOTDIR) /* "notes.yaml/out.yaml": a file where the folder should be */
            return lv_fail(err, LV_ERR_INPUT, "'%s': a part of its folder is a file, not a "
                           "folder", path);
        return lv_fail(err, LV_ERR_INPUT, "'%s': %s", path, lv_strerror(errno, text, sizeof text));
    }
    if (S_ISDIR(so.st_mode))
        return lv_fail(err, LV_ERR_INPUT, "'%s' is a folder: name the file to write", path);
    for (size_t i = 0; m != NULL && i < lv_mission_file_count(m); i++) {
        const char *in = lv_mission_file(m, i);
        struct stat si;
        if (stat(in, &si) == 0 && si.st_dev == so.st_dev && si.st_ino == so.st_ino)
            return lv_fail(err, LV_ERR_INPUT,
                           "cannot write '%s': it is the mission's %s '%s' (the same file): "
                           "lvsim never replaces what it reads, also with --force; choose "
                           "another output",
                           path, i == 0 ? "file" : "data file", in);
    }
    if (link)
        return lv_fail(err, LV_ERR_INPUT, link_msg, path);
    if (!(flags & LV_OUTPUT_REPLACE))
        return lv_fail(err, LV_ERR_INPUT,
                       "'%s' exists: lvsim does not replace a file it cannot prove it wrote; "
                       "choose another name, or add --force to replace it",
                       path);
    if (!S_ISREG(so.st_mode))
        return lv_fail(err, LV_ERR_INPUT, "'%s' is not a regular file: it is not replaced", path);
    return LV_OK;
}
