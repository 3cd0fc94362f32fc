/* Store files on POSIX systems: what loading reads (regular files within the load cap only) and what
   saving leaves behind (the old file or the whole new one, its permissions, links written through, no
   temporary file after a failure, stale temporary files of killed saves removed by the next save, two
   processes saving at once both succeed). */
#define _POSIX_C_SOURCE 200809L
#include "harness.h"

#ifndef _WIN32

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define DIR_NAME "harness_files"

static int error_mentions(const char* word) { return strstr(tp_last_error(), word) != NULL; }

/* Temporary files of saves ("*.tetprobe-tmp-*") in DIR_NAME. */
static int count_temporaries(void) {
    DIR* dir = opendir(DIR_NAME);
    struct dirent* entry;
    int count = 0;
    if (!dir) return -1;
    while ((entry = readdir(dir)) != NULL) count += strstr(entry->d_name, ".tetprobe-tmp-") != NULL;
    closedir(dir);
    return count;
}

static int exists(const char* path) {
    struct stat st;
    return lstat(path, &st) == 0;
}

/* Whether the file at path loads and holds exactly the store's blob. */
static int holds_store(const char* path, const tp_store* store) {
    tp_store* copy = NULL;
    const void *a, *b;
    size_t size_a = 0, size_b = 0;
    int same;
    if (tp_store_load_file(path, &copy) != TP_OK) return 0;
    tp_store_blob(store, &a, &size_a);
    tp_store_blob(copy, &b, &size_b);
    same = size_a == size_b && memcmp(a, b, size_a) == 0;
    tp_store_release(copy);
    return same;
}

static void write_bytes(const char* path, const char* text) {
    FILE* f = fopen(path, "wb");
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

/* A process id that no process has now (a child that has exited and been reaped). */
static pid_t dead_pid(void) {
    pid_t child = fork();
    if (child == 0) _exit(0);
    waitpid(child, NULL, 0);
    return child;
}

static void test_loading_refuses(const tp_store* store) {
    tp_store* loaded = NULL;
    tp_store_load_options options;
    const char* path = DIR_NAME "/cap.tpb";
    struct stat st;
    /* /dev/zero used to be read until memory ran out; a FIFO without a writer used to block. */
    EXPECT_STATUS(tp_store_load_file("/dev/zero", &loaded), TP_ERROR_IO);
    CHECK(error_mentions("character device") && error_mentions("not a regular file"));
    EXPECT_STATUS(tp_store_load_file(DIR_NAME, &loaded), TP_ERROR_IO);
    CHECK(error_mentions("a directory"));
    CHECK(mkfifo(DIR_NAME "/fifo", 0600) == 0);
    EXPECT_STATUS(tp_store_load_file(DIR_NAME "/fifo", &loaded), TP_ERROR_IO);
    CHECK(error_mentions("a FIFO"));
    remove(DIR_NAME "/fifo");
    CHECK(loaded == NULL);

    /* The load cap: the default is 1 GiB; a file one byte above a smaller cap is refused, at it loads. */
    EXPECT_OK(tp_store_load_options_init(&options));
    CHECK(options.struct_size == sizeof options);
    CHECK(options.max_file_bytes == ((uint64_t)1 << 30));
    EXPECT_OK(tp_store_save_file(store, path));
    CHECK(stat(path, &st) == 0);
    options.max_file_bytes = (uint64_t)st.st_size - 1;
    EXPECT_STATUS(tp_store_load_file_ex(path, &options, &loaded), TP_ERROR_IO);
    CHECK(error_mentions("above the load cap") && mentions_number(tp_last_error(), (unsigned long)st.st_size - 1));
    CHECK(loaded == NULL);
    options.max_file_bytes = (uint64_t)st.st_size;
    EXPECT_OK(tp_store_load_file_ex(path, &options, &loaded));
    tp_store_release(loaded);
    loaded = NULL;
    EXPECT_OK(tp_store_load_file_ex(path, NULL, &loaded));
    tp_store_release(loaded);
    loaded = NULL;
    options.struct_size = 0;
    EXPECT_STATUS(tp_store_load_file_ex(path, &options, &loaded), TP_ERROR_INVALID_ARGUMENT);
    /* An older caller's struct without the field keeps the default cap. */
    options.struct_size = sizeof(uint32_t);
    options.max_file_bytes = 1;
    EXPECT_OK(tp_store_load_file_ex(path, &options, &loaded));
    tp_store_release(loaded);
    loaded = NULL;
    EXPECT_STATUS(tp_store_load_file_ex(NULL, NULL, &loaded), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load_file_ex(path, NULL, NULL), TP_ERROR_INVALID_ARGUMENT);
    remove(path);
}

static void test_saving_keeps_mode_and_links(const tp_store* store) {
    const char* path = DIR_NAME "/mode.tpb";
    struct stat st;
    mode_t mask = umask(022);
    /* A new file gets the default of any new file (0666 less the umask); an existing one keeps its mode. */
    EXPECT_OK(tp_store_save_file(store, path));
    CHECK(stat(path, &st) == 0 && (st.st_mode & 07777) == 0644);
    CHECK(chmod(path, 0600) == 0);
    EXPECT_OK(tp_store_save_file(store, path));
    CHECK(stat(path, &st) == 0 && (st.st_mode & 07777) == 0600);
    CHECK(chmod(path, 0640) == 0);
    EXPECT_OK(tp_store_save_file(store, path));
    CHECK(stat(path, &st) == 0 && (st.st_mode & 07777) == 0640);
    remove(path);
    umask(mask);

    /* A symbolic link is written through: the link stays, its target gets the store (relative and
       chained links, and a dangling one whose target is created). */
    CHECK(mkdir(DIR_NAME "/real", 0755) == 0);
    write_bytes(DIR_NAME "/real/target.tpb", "old contents");
    CHECK(symlink("real/target.tpb", DIR_NAME "/link.tpb") == 0);
    CHECK(symlink("link.tpb", DIR_NAME "/link2.tpb") == 0);
    EXPECT_OK(tp_store_save_file(store, DIR_NAME "/link2.tpb"));
    CHECK(lstat(DIR_NAME "/link.tpb", &st) == 0 && S_ISLNK(st.st_mode));
    CHECK(lstat(DIR_NAME "/link2.tpb", &st) == 0 && S_ISLNK(st.st_mode));
    CHECK(holds_store(DIR_NAME "/real/target.tpb", store));
    CHECK(symlink("real/new.tpb", DIR_NAME "/dangling.tpb") == 0);
    EXPECT_OK(tp_store_save_file(store, DIR_NAME "/dangling.tpb"));
    CHECK(lstat(DIR_NAME "/dangling.tpb", &st) == 0 && S_ISLNK(st.st_mode));
    CHECK(holds_store(DIR_NAME "/real/new.tpb", store));
    CHECK(symlink("loop_b.tpb", DIR_NAME "/loop_a.tpb") == 0 && symlink("loop_a.tpb", DIR_NAME "/loop_b.tpb") == 0);
    EXPECT_STATUS(tp_store_save_file(store, DIR_NAME "/loop_a.tpb"), TP_ERROR_IO);
    CHECK(error_mentions("symbolic links"));
    /* Not a regular file: refused, and left as it was (renaming over a FIFO would replace it). */
    CHECK(mkfifo(DIR_NAME "/fifo.tpb", 0600) == 0);
    EXPECT_STATUS(tp_store_save_file(store, DIR_NAME "/fifo.tpb"), TP_ERROR_IO);
    CHECK(error_mentions("a FIFO") && lstat(DIR_NAME "/fifo.tpb", &st) == 0 && S_ISFIFO(st.st_mode));
    EXPECT_STATUS(tp_store_save_file(store, DIR_NAME "/real"), TP_ERROR_IO);
    CHECK(count_temporaries() == 0);
    remove(DIR_NAME "/fifo.tpb");
    remove(DIR_NAME "/loop_a.tpb");
    remove(DIR_NAME "/loop_b.tpb");
    remove(DIR_NAME "/dangling.tpb");
    remove(DIR_NAME "/link.tpb");
    remove(DIR_NAME "/link2.tpb");
    remove(DIR_NAME "/real/new.tpb");
    remove(DIR_NAME "/real/target.tpb");
    rmdir(DIR_NAME "/real");
}

static void test_saving_leaves_no_temporary_file(const tp_store* store) {
    const char* path = DIR_NAME "/fail.tpb";
    const void* blob;
    size_t size = 0;
    struct rlimit old_limit, small;
    char name[256];
    pid_t gone = dead_pid();
    tp_store_blob(store, &blob, &size);
    write_bytes(path, "old contents");

    /* A write that fails half-way (the file size limit) removes the temporary file; the old file stays. */
    signal(SIGXFSZ, SIG_IGN);
    CHECK(getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
    small = old_limit;
    small.rlim_cur = (rlim_t)(size / 2);
    CHECK(setrlimit(RLIMIT_FSIZE, &small) == 0);
    EXPECT_STATUS(tp_store_save_file(store, path), TP_ERROR_IO);
    CHECK(setrlimit(RLIMIT_FSIZE, &old_limit) == 0);
    signal(SIGXFSZ, SIG_DFL);
    CHECK(count_temporaries() == 0);
    {
        size_t read_size = 0;
        unsigned char* bytes = read_whole_file(path, &read_size);
        CHECK(bytes && read_size == 12 && memcmp(bytes, "old contents", 12) == 0);
        free(bytes);
    }

    /* Temporary files a killed save left: the next save of the same file removes those of its pattern
       whose process is gone; a live process's, this process's own, another file's, and names that only
       look alike stay. */
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-0123456789abcdef", (long)gone);
    write_bytes(name, "stale");
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-00000000000000ff", (long)gone);
    write_bytes(name, "stale");
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-1-0123456789abcdef"); /* init is alive */
    write_bytes(name, "live");
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-0123456789abcdef", (long)getpid());
    write_bytes(name, "own");
    sprintf(name, DIR_NAME "/other.tpb.tetprobe-tmp-%ld-0123456789abcdef", (long)gone);
    write_bytes(name, "other file's");
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-0123456789ABCDEF", (long)gone);
    write_bytes(name, "not the pattern");
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-0123456789abcdef.bak", (long)gone);
    write_bytes(name, "not the pattern");
    CHECK(count_temporaries() == 7);
    EXPECT_OK(tp_store_save_file(store, path));
    CHECK(holds_store(path, store));
    CHECK(count_temporaries() == 5);
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-0123456789abcdef", (long)gone);
    CHECK(!exists(name));
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-1-0123456789abcdef");
    CHECK(exists(name));
    remove(name);
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-0123456789abcdef", (long)getpid());
    CHECK(exists(name));
    remove(name);
    sprintf(name, DIR_NAME "/other.tpb.tetprobe-tmp-%ld-0123456789abcdef", (long)gone);
    remove(name);
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-0123456789ABCDEF", (long)gone);
    remove(name);
    sprintf(name, DIR_NAME "/fail.tpb.tetprobe-tmp-%ld-0123456789abcdef.bak", (long)gone);
    remove(name);
    CHECK(count_temporaries() == 0);
    remove(path);
}

/* Saves killed at random moments leave at most their temporary file, never a part of the store at the
   path; the next save removes it. Two processes saving the same file at once both succeed. */
static void test_killed_and_concurrent_saves(const tp_store* store) {
    const char* path = DIR_NAME "/busy.tpb";
    int round, ok = 1;
    pid_t child;
    int status = 0;
    EXPECT_OK(tp_store_save_file(store, path));
    for (round = 0; round < 8; ++round) {
        struct timespec pause;
        child = fork();
        if (child == 0) {
            for (;;) tp_store_save_file(store, path);
        }
        pause.tv_sec = 0;
        pause.tv_nsec = 2000000L + 3000000L * round;
        nanosleep(&pause, NULL);
        kill(child, SIGKILL);
        waitpid(child, NULL, 0);
        ok &= holds_store(path, store); /* the old or the new bytes, whole */
        ok &= tp_store_save_file(store, path) == TP_OK;
        ok &= count_temporaries() == 0;
    }
    CHECK(ok);
    child = fork();
    if (child == 0) {
        int i, failures = 0;
        for (i = 0; i < 40; ++i) failures += tp_store_save_file(store, path) != TP_OK;
        _exit(failures == 0 ? 0 : 1);
    }
    for (round = 0; round < 40; ++round) ok &= tp_store_save_file(store, path) == TP_OK;
    waitpid(child, &status, 0);
    CHECK(ok);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    CHECK(holds_store(path, store));
    CHECK(count_temporaries() == 0);
    remove(path);
}

void test_store_files(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    tp_store* store = build_cloud(positions, sh, 0);
    if (!store) return;
    mkdir(DIR_NAME, 0755);
    test_loading_refuses(store);
    test_saving_keeps_mode_and_links(store);
    test_saving_leaves_no_temporary_file(store);
    test_killed_and_concurrent_saves(store);
    rmdir(DIR_NAME);
    tp_store_release(store);
}

#else

void test_store_files(void) {}

#endif
