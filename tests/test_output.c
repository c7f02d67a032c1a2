/* Output files never destroy data (pointnpr/output.h): temporaries created exclusively and
 * removed on failure and on signals, special files written through, links, the input refused,
 * the system's reason for a failed write. Everything happens in a folder of the test's own. */
#include "testutil.h"

#include <pointnpr/output.h>

#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define DIR_ PNPR_TEST_SCRATCH "/output"

static void put(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (f) { fputs(text, f); fclose(f); }
}

/* The file's content (at most 255 bytes) in buf; "" when it cannot be read. */
static const char *get(const char *path, char *buf)
{
    buf[0] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f) return buf;
    size_t n = fread(buf, 1, 255, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Number of temporaries in DIR_, of any output. */
static int temporaries(void)
{
    return pnpr_test_temporaries(DIR_, "");
}

static int print_hello(FILE *f, const void *ctx)
{
    return fprintf(f, "%s", (const char *)ctx) < 0;
}

static void test_replace_regular(void)
{
    char buf[256];
    pnpr_error e = {0};
    CHECK_STATUS(pnpr_output_write(DIR_ "/new.txt", print_hello, "one", &e), PNPR_OK);
    CHECK(!strcmp(get(DIR_ "/new.txt", buf), "one"));
    /* an existing file keeps its permission bits */
    chmod(DIR_ "/new.txt", 0640);
    CHECK_STATUS(pnpr_output_write(DIR_ "/new.txt", print_hello, "two", &e), PNPR_OK);
    struct stat sb;
    CHECK(stat(DIR_ "/new.txt", &sb) == 0 && (sb.st_mode & 0777) == 0640);
    CHECK(!strcmp(get(DIR_ "/new.txt", buf), "two"));
    CHECK(temporaries() == 0);

    /* while open: one temporary ".new.txt.<16 hex>.part" beside it; a failed writer keeps the old file */
    pnpr_output o;
    CHECK_STATUS(pnpr_output_open(&o, DIR_ "/new.txt", &e), PNPR_OK);
    CHECK(temporaries() == 1);
    const char *base = strrchr(o.tmp, '/') + 1;
    CHECK(!strncmp(base, ".new.txt.", 9) && strlen(base) == 9 + 16 + 5);
    fputs("half", o.f);
    CHECK_STATUS(pnpr_output_close(&o, PNPR_ERR_CANCELLED, &e), PNPR_ERR_CANCELLED);
    CHECK(!strcmp(get(DIR_ "/new.txt", buf), "two"));
    CHECK(temporaries() == 0);
}

static void test_planted_names(void)
{
    char buf[256];
    pnpr_error e = {0};
    /* the names earlier versions used, planted as links to a victim, and a user's own OUT.tmp */
    put(DIR_ "/victim", "victim");
    put(DIR_ "/out.png.tmp", "mine");
    CHECK(symlink("victim", DIR_ "/out.png.tmp-png") == 0);
    CHECK(symlink("victim", DIR_ "/out.png.part") == 0);
    CHECK_STATUS(pnpr_output_write(DIR_ "/out.png", print_hello, "image", &e), PNPR_OK);
    CHECK(!strcmp(get(DIR_ "/victim", buf), "victim"));
    CHECK(!strcmp(get(DIR_ "/out.png.tmp", buf), "mine"));
    CHECK(!strcmp(get(DIR_ "/out.png", buf), "image"));
}

static void test_links_and_kinds(void)
{
    char buf[256];
    pnpr_error e = {0};
    struct stat sb;
    /* a link to a regular file: the file is replaced, the link stays */
    put(DIR_ "/real.txt", "old");
    CHECK(symlink("real.txt", DIR_ "/link.txt") == 0);
    CHECK_STATUS(pnpr_output_write(DIR_ "/link.txt", print_hello, "new", &e), PNPR_OK);
    CHECK(lstat(DIR_ "/link.txt", &sb) == 0 && S_ISLNK(sb.st_mode));
    CHECK(!strcmp(get(DIR_ "/real.txt", buf), "new"));
    /* a dangling link and a directory are refused, nothing is created */
    CHECK(symlink("nowhere.txt", DIR_ "/dangling.txt") == 0);
    CHECK_STATUS(pnpr_output_write(DIR_ "/dangling.txt", print_hello, "x", &e), PNPR_ERR_IO);
    CHECK(strstr(e.message, "dangling.txt") && strstr(e.message, "link to nothing"));
    CHECK(stat(DIR_ "/nowhere.txt", &sb) != 0);
    mkdir(DIR_ "/sub.txt", 0755);
    CHECK_STATUS(pnpr_output_write(DIR_ "/sub.txt", print_hello, "x", &e), PNPR_ERR_IO);
    CHECK(strstr(e.message, "is a directory"));
    /* a device is written through and stays a device; /dev/full says why it failed */
    CHECK_STATUS(pnpr_output_write("/dev/null", print_hello, "x", &e), PNPR_OK);
    CHECK(stat("/dev/null", &sb) == 0 && S_ISCHR(sb.st_mode));
    if (stat("/dev/full", &sb) == 0) {
        CHECK_STATUS(pnpr_output_write("/dev/full", print_hello, "x", &e), PNPR_ERR_IO);
        CHECK_MSG(strstr(e.message, "No space left on device"), "%s", e.message);
    }
    CHECK(temporaries() == 0);
}

static void test_fifo(void)
{
    CHECK(mkfifo(DIR_ "/pipe", 0600) == 0);
    pid_t pid = fork();
    if (pid == 0) { /* the reader */
        char buf[256];
        FILE *f = fopen(DIR_ "/pipe", "rb");
        size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
        buf[n] = '\0';
        _exit(strcmp(buf, "through a pipe") == 0 ? 0 : 1);
    }
    pnpr_error e = {0};
    CHECK_STATUS(pnpr_output_write(DIR_ "/pipe", print_hello, "through a pipe", &e), PNPR_OK);
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    struct stat sb;
    CHECK(lstat(DIR_ "/pipe", &sb) == 0 && S_ISFIFO(sb.st_mode));
}

static void test_check(void)
{
    pnpr_error e = {0};
    put(DIR_ "/in.ply", "ply");
    CHECK(link(DIR_ "/in.ply", DIR_ "/hard.ply") == 0);
    CHECK(symlink("in.ply", DIR_ "/soft.ply") == 0);
    const char *in[] = {DIR_ "/other.ply", DIR_ "/in.ply"};
    CHECK_STATUS(pnpr_output_check(DIR_ "/in.ply", in, 2, &e), PNPR_ERR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "is the input"));
    CHECK_STATUS(pnpr_output_check(DIR_ "/hard.ply", in, 2, &e), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_output_check(DIR_ "/soft.ply", in, 2, &e), PNPR_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(pnpr_output_check(DIR_ "/out.ply", in, 2, &e), PNPR_OK);
    CHECK_STATUS(pnpr_output_check("-", in, 2, &e), PNPR_OK);
    CHECK_STATUS(pnpr_output_check(DIR_ "/missing/out.ply", in, 2, &e), PNPR_ERR_IO);
    CHECK(strstr(e.message, "cannot write into the folder"));
    CHECK_STATUS(pnpr_output_check(DIR_ "/sub.txt", in, 2, &e), PNPR_ERR_IO);
    CHECK_STATUS(pnpr_output_check("", in, 2, &e), PNPR_ERR_INVALID_ARGUMENT);
    if (geteuid() != 0) { /* root may write anything: the protection only holds for users */
        put(DIR_ "/ro.ply", "keep");
        chmod(DIR_ "/ro.ply", 0444);
        CHECK_STATUS(pnpr_output_check(DIR_ "/ro.ply", in, 2, &e), PNPR_ERR_IO);
        CHECK_STATUS(pnpr_output_write(DIR_ "/ro.ply", print_hello, "x", &e), PNPR_ERR_IO);
    }
}

/* A process killed while it writes leaves the old file and no temporary. */
static void test_signal(void)
{
    char buf[256];
    put(DIR_ "/sig.txt", "before");
    pid_t pid = fork();
    if (pid == 0) {
        pnpr_output_cleanup_on_signals();
        pnpr_output o;
        if (pnpr_output_open(&o, DIR_ "/sig.txt", NULL) != PNPR_OK) _exit(3);
        fputs("during", o.f);
        fflush(o.f);
        raise(SIGTERM);
        _exit(4); /* not reached: the handler ends the process with SIGTERM */
    }
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK_MSG(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM, "status %d", status);
    CHECK(temporaries() == 0);
    CHECK(!strcmp(get(DIR_ "/sig.txt", buf), "before"));

    /* the same removal, called directly: the close that follows fails and keeps the old file */
    pnpr_output o;
    pnpr_error e = {0};
    CHECK_STATUS(pnpr_output_open(&o, DIR_ "/sig.txt", &e), PNPR_OK);
    CHECK(temporaries() == 1);
    pnpr_output_remove_temporaries();
    CHECK(temporaries() == 0);
    CHECK_STATUS(pnpr_output_close(&o, PNPR_OK, &e), PNPR_ERR_IO);
    CHECK(!strcmp(get(DIR_ "/sig.txt", buf), "before"));
}

int main(void)
{
    if (system("rm -rf '" DIR_ "' && mkdir -p '" DIR_ "'") != 0) return 1;
    test_replace_regular();
    test_planted_names();
    test_links_and_kinds();
    test_fifo();
    test_check();
    test_signal();
    return pnpr_test_finish("test_output");
}
