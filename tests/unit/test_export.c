/* test_export.c - trajectory exports (CZML, KML, CCSDS OEM) from results folders: runs the
 * paper's test case (flat world) and the dof3 branch mission (rotating Earth) into
 * export_out/{paper,dof3}, exports them, checks what C can (files, document structure, the
 * clock interval against the phase times, error cases). tests/python/check_exports.py then
 * checks the documents against the formats' rules (ctest fixture "export_files"). */
#define _POSIX_C_SOURCE 200809L

#include <cjson/cJSON.h>
#include <fnmatch.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "lvsim/lv_export.h"
#include "lvsim/lv_mission.h"
#include "lvsim/lv_summary.h"
#include "post/export_int.h"
#include "post/json_print.h"

static char path_buf[4096];
static const char *src_path(const char *rel)
{
    const char *root = getenv("LV_SOURCE_DIR");
    snprintf(path_buf, sizeof path_buf, "%s/%s", root ? root : "..", rel);
    return path_buf;
}

static int exists(const char *dir, const char *file)
{
    char p[4096];
    struct stat sb;
    snprintf(p, sizeof p, "%s/%s", dir, file);
    return stat(p, &sb) == 0 && sb.st_size > 0;
}

static char *slurp(const char *dir, const char *file)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/%s", dir, file);
    FILE *f = fopen(p, "rb");
    if (f == NULL)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s != NULL) {
        size_t got = fread(s, 1, (size_t)n, f);
        s[got] = '\0';
    }
    fclose(f);
    return s;
}

static void copy_file(const char *from_dir, const char *to_dir, const char *file)
{
    char *s = slurp(from_dir, file);
    char p[4096];
    snprintf(p, sizeof p, "%s/%s", to_dir, file);
    FILE *f = fopen(p, "wb");
    CHECK(s != NULL && f != NULL);
    if (s != NULL && f != NULL)
        fputs(s, f);
    if (f != NULL)
        fclose(f);
    free(s);
}

/* Runs a mission into outdir and writes its summary; returns 0 on success. */
static int run_mission(const char *rel, const char *outdir)
{
    lv_err err = {0};
    lv_mission *m = NULL;
    CHECK_OK(lv_mission_load(src_path(rel), &m, &err), &err);
    if (m == NULL)
        return -1;
    lv_run_options opt = {0};
    opt.outdir = outdir;
    opt.threads = 1;
    lv_run *run = NULL;
    lv_status st = lv_run_create(m, &run, &err);
    if (st == LV_OK)
        st = lv_run_execute(run, &opt, &err);
    CHECK_OK(st, &err);
    if (st == LV_OK) {
        st = lv_run_write_summary(run, outdir, &err);
        CHECK_OK(st, &err);
    }
    lv_run_free(run);
    lv_mission_free(m);
    return st == LV_OK ? 0 : -1;
}

/* Latest t_end of the summary's done phases (s). */
static double mission_end(const char *dir)
{
    char *text = slurp(dir, "summary.json");
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    free(text);
    double t1 = -1.0;
    const cJSON *p;
    cJSON_ArrayForEach(p, cJSON_GetObjectItem(root, "phases"))
    {
        const cJSON *te = cJSON_GetObjectItem(p, "t_end");
        if (cJSON_IsNumber(te) && te->valuedouble > t1)
            t1 = te->valuedouble;
    }
    cJSON_Delete(root);
    return t1;
}

/* "2026-03-01T12:00:00Z/<epoch + t1>": both missions start at 12:00:00 and last < 1 h. */
static void mission_interval(double t1, char *buf, size_t cap)
{
    const long long us = llround(t1 * 1e6);
    snprintf(buf, cap, "2026-03-01T12:00:00Z/2026-03-01T12:%02lld:%02lld.%06lldZ",
             us / 60000000LL, us / 1000000LL % 60, us % 1000000LL);
}

/* The CZML: document packet first, then one track per (body, phase) of the summary, then
 * markers; the clock interval spans the done phases. */
static void check_czml(const char *dir, int n_tracks, const char *interval)
{
    char *text = slurp(dir, "mission.czml");
    cJSON *doc = text ? cJSON_Parse(text) : NULL;
    free(text);
    CHECK(cJSON_IsArray(doc));
    if (!cJSON_IsArray(doc))
        return;
    const cJSON *d = cJSON_GetArrayItem(doc, 0);
    CHECK(strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(d, "id")), "document") == 0);
    CHECK(strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(d, "version")), "1.0") == 0);
    const cJSON *clock = cJSON_GetObjectItem(d, "clock");
    const char *iv = cJSON_GetStringValue(cJSON_GetObjectItem(clock, "interval"));
    CHECK(iv != NULL && strcmp(iv, interval) == 0);
    if (iv != NULL && strcmp(iv, interval) != 0)
        fprintf(stderr, "  interval %s, expected %s\n", iv, interval);
    int tracks = 0, events = 0;
    const cJSON *p;
    cJSON_ArrayForEach(p, doc)
    {
        const char *id = cJSON_GetStringValue(cJSON_GetObjectItem(p, "id"));
        tracks += id != NULL && strncmp(id, "track/", 6) == 0;
        events += id != NULL && strncmp(id, "event/", 6) == 0;
        if (id != NULL && strncmp(id, "track/", 6) == 0) {
            const cJSON *av = cJSON_GetObjectItem(p, "availability");
            CHECK(cJSON_IsString(av) && strcmp(av->valuestring, interval) == 0);
        }
    }
    CHECK(tracks == n_tracks);
    CHECK(events > 0);
    cJSON_Delete(doc);
}

/* Replaces every occurrence of `from` in dir/file by `to`. */
static void replace_in(const char *dir, const char *file, const char *from, const char *to)
{
    char *s = slurp(dir, file), p[4096];
    snprintf(p, sizeof p, "%s/%s", dir, file);
    FILE *f = fopen(p, "wb");
    CHECK(s != NULL && f != NULL);
    for (const char *c = s; c != NULL && f != NULL && *c;) {
        const char *hit = strstr(c, from);
        size_t n = hit ? (size_t)(hit - c) : strlen(c);
        fwrite(c, 1, n, f);
        if (hit == NULL)
            break;
        fputs(to, f);
        c = hit + strlen(from);
    }
    if (f != NULL)
        fclose(f);
    free(s);
}

/* The CZML is laid out as cJSON_Print lays out the document it holds, its numbers exact (the
 * writer streams it in that layout: export_czml.c): cJSON (an independent JSON implementation)
 * parses the file and lv_json_print (cJSON_Print with each number's shortest round-trip text,
 * checked against strtod and printf in test_json_numbers) prints it again byte for byte;
 * `track_id`, when given, is the id of one of its packets (names from the mission, escaped
 * and read back). */
static void check_czml_layout(const char *dir, const char *track_id)
{
    char *text = slurp(dir, "mission.czml");
    cJSON *doc = text ? cJSON_Parse(text) : NULL;
    char *again = doc ? lv_json_print(doc) : NULL;
    CHECK(again != NULL);
    if (again != NULL) {
        const size_t n = strlen(again);
        CHECK(strlen(text) == n + 1 && strncmp(text, again, n) == 0 && text[n] == '\n');
    }
    if (track_id != NULL) {
        int found = 0;
        const cJSON *p;
        cJSON_ArrayForEach(p, doc)
        {
            const char *id = cJSON_GetStringValue(cJSON_GetObjectItem(p, "id"));
            found += id != NULL && strcmp(id, track_id) == 0;
        }
        CHECK(found == 1);
    }
    cJSON_free(again);
    cJSON_Delete(doc);
    free(text);
}

/* The fewest significant digits p (1..17) with which printf's correctly rounded "%.*e" reads
 * back (strtod) to d: the length of the shortest round-trip text, found independently of
 * Dragonbox (glibc's printf and strtod are exact). */
static int shortest_digits(double d)
{
    for (int p = 1; p <= 17; p++) {
        char b[64];
        snprintf(b, sizeof b, "%.*e", p - 1, d);
        if (strtod(b, NULL) == d)
            return p;
    }
    return 17;
}

/* Significant digits of a decimal text: those of its mantissa without leading zeros and,
 * past the decimal point, without trailing zeros ("100" counts 1, "0.0012" 2). */
static int digits_of(const char *t)
{
    char m[64];
    size_t k = 0;
    for (const char *c = t; *c && *c != 'e' && *c != 'E' && k + 1 < sizeof m; c++)
        if (*c >= '0' && *c <= '9')
            m[k++] = *c;
    m[k] = '\0';
    size_t lo = 0, hi = k;
    while (lo < hi && m[lo] == '0')
        lo++;
    while (hi > lo && m[hi - 1] == '0')
        hi--;
    return hi > lo ? (int)(hi - lo) : 1;
}

/* lv_ex_json_number (the CZML's numbers) and lv_json_print (every other JSON file) against
 * independent references, for numbers of every kind (integers, int overflow, 15- and 17-digit
 * values, subnormals, NaN and infinities, random bit patterns): the text reads back (strtod)
 * to the same double, bit for bit (-0.0 too); it has the fewest significant digits that do
 * (shortest_digits); cJSON parses it to the same double; NaN and the infinities are null.
 * Beside it, how often cJSON 1.7.15's own printer writes a number that reads back to another
 * double (the reason for all this; printed, asserted to happen). Then lv_ex_json_string
 * against cJSON's escapes (strings with every escape, control characters and UTF-8). */
static void test_json_numbers(void)
{
    const double fixed[] = {0.0, -0.0, 1.0, -1.0, 8.0, 255.0, 0.5, 0.1, 1.0 / 3.0,
                            100.00000000011187, -52.775, 5.2359999997184534, 1e15, 1e16,
                            1e17, 123456789012345.6, 2147483647.0, 2147483648.0,
                            -2147483648.0, -2147483649.0, 2147483647.5, 1e300, -1e-300,
                            4.9e-324, 2.2250738585072014e-308, 1e-5, 1.5e-4, NAN, INFINITY,
                            -INFINITY, 1089.0782, 0.1 + 0.2, 190.80430311868503};
    int bad = 0, cjson_lossy = 0, trajectory_like = 0;
    unsigned long long x = 0x9e3779b97f4a7c15ULL; /* xorshift64 (Marsaglia 2003) */
    for (int i = 0; i < 20000; i++) {
        double d;
        int traj = 0;
        if (i < (int)(sizeof fixed / sizeof fixed[0])) {
            d = fixed[i];
        } else {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            if (i % 2) { /* any bit pattern */
                memcpy(&d, &x, sizeof d);
            } else { /* trajectory-like: |d| < 1e6, few to 17 digits */
                d = (double)(x >> 11) / 9007199254740992.0 * 2e6 - 1e6;
                if (i % 4 == 0)
                    d = (double)(long long)(d * 1000.0) / 1000.0;
                traj = 1;
            }
        }
        char mine[LV_EX_JSON_NUM_CAP];
        const size_t n = lv_ex_json_number(d, mine);
        cJSON *num = cJSON_CreateNumber(d);
        char *doc = lv_json_print(num); /* the same text from the document printer */
        char *ref = cJSON_PrintUnformatted(num);
        int ok = strlen(mine) == n && doc != NULL && strcmp(doc, mine) == 0;
        if (ok && !isfinite(d)) {
            ok = strcmp(mine, "null") == 0;
        } else if (ok) {
            char *end = NULL;
            const double back = strtod(mine, &end);
            cJSON *parsed = cJSON_Parse(mine);
            ok = *end == '\0' && memcmp(&back, &d, sizeof d) == 0 &&
                 digits_of(mine) == shortest_digits(d) && cJSON_IsNumber(parsed) &&
                 parsed->valuedouble == d;
            cJSON_Delete(parsed);
            if (traj) {
                trajectory_like++;
                cjson_lossy += ref != NULL && strtod(ref, NULL) != d;
            }
        }
        if (!ok && bad++ < 5)
            fprintf(stderr, "  %.17g: '%s' (document '%s')\n", d, mine, doc ? doc : "?");
        cJSON_free(doc);
        cJSON_free(ref);
        cJSON_Delete(num);
    }
    CHECK(bad == 0);
    printf("  cJSON 1.7.15's printer: %d of %d trajectory-like numbers read back to another "
           "double\n", cjson_lossy, trajectory_like);
    CHECK(cjson_lossy > 0);

    const char *strs[] = {"", "plain", "q\"uote", "back\\slash", "\b\f\n\r\t", "\x01\x1f\x7f",
                          "\xc3\xa9t\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\x80", "/slash", "\xff"};
    for (size_t i = 0; i < sizeof strs / sizeof strs[0]; i++) {
        char buf[256] = {0};
        FILE *f = fmemopen(buf, sizeof buf - 1, "w");
        CHECK(f != NULL);
        if (f == NULL)
            continue;
        lv_ex_json_string(f, strs[i]);
        fclose(f);
        cJSON *str = cJSON_CreateString(strs[i]);
        char *ref = cJSON_PrintUnformatted(str);
        CHECK(ref != NULL && strcmp(ref, buf) == 0);
        if (ref != NULL && strcmp(ref, buf) != 0)
            fprintf(stderr, "  string %zu: %s, cJSON %s\n", i, buf, ref);
        cJSON_free(ref);
        cJSON_Delete(str);
    }
}

/* lv_ex_clock_iso against lv_ex_iso / lv_ex_iso_no60 (lv_utc_format, ERFA for every call):
 * one time every 0.1234567 s (and on whole seconds) across the leap second at the end of
 * 2016 (23:59:60 in the one, 23:59:59.999999 in the other), across a midnight of 1965 (TAI -
 * UTC a fraction of a second: never cached) and of 1955 (before UTC: TAI - UTC taken as 0). */
static void test_clock(void)
{
    static const char *const epochs[] = {"2016-12-31T23:59:00Z", "1965-06-30T23:59:30Z",
                                         "1955-01-01T23:59:30Z"};
    int bad = 0;
    for (size_t e = 0; e < sizeof epochs / sizeof epochs[0]; e++) {
        lv_ex_run r;
        memset(&r, 0, sizeof r);
        CHECK(lv_utc_parse(epochs[e], &r.epoch) >= 0);
        for (int no60 = 0; no60 < 2; no60++) {
            lv_ex_clock c = {0};
            for (int i = 0; i < 1500; i++) {
                const double t = i % 3 == 0 ? (double)(i / 3) : i * 0.1234567;
                char a[48], b[48];
                const int la = lv_ex_clock_iso(&r, &c, t, no60, "Z", a, sizeof a);
                int lb = 0;
                if (no60)
                    lb = lv_ex_iso_no60(&r, t, "Z", b, sizeof b);
                else
                    lv_ex_iso(&r, t, "Z", b, sizeof b);
                if (strcmp(a, b) != 0 || la != lb) {
                    if (bad++ < 5)
                        fprintf(stderr, "  %s + %.7f s: '%s' (%d), expected '%s' (%d)\n",
                                epochs[e], t, a, la, b, lb);
                }
            }
        }
    }
    CHECK(bad == 0);
}

/* A copy of the paper folder whose mission and phase P4 carry XML and CSV metacharacters:
 * the phase name `P4, <&> "q" 's'` is a quoted CSV field. check_exports.py parses the KML. */
static void names_folder(const char *paper)
{
    const char *dir = "export_out/names";
    const char *files[] = {"summary.json", "body_stage1.csv", "body_stage2.csv",
                           "body_stage3.csv"};
    mkdir(dir, 0777);
    for (int i = 0; i < 4; i++)
        copy_file(paper, dir, files[i]);
    replace_in(dir, "body_stage1.csv", ",P4,", ",\"P4, <&> \"\"q\"\" 's'\",");
    replace_in(dir, "summary.json", "\"P4\"", "\"P4, <&> \\\"q\\\" 's'\"");
    replace_in(dir, "summary.json", "\"paper-test-case\"",
               "\"paper & <test> \\\"case\\\" 'x'\"");
    /* P3: a JSON quote and backslash, UTF-8 letters (e acute, n tilde) */
    replace_in(dir, "body_stage3.csv", ",P3,", ",\"P3 \"\"\xc3\xa9\"\" \\ \xc3\xb1\",");
    replace_in(dir, "summary.json", "\"P3\"", "\"P3 \\\"\xc3\xa9\\\" \\\\ \xc3\xb1\"");
    lv_err err = {0};
    CHECK_OK(lv_export_run(dir, LV_EXPORT_ALL, &err), &err);
    check_czml_layout(dir, "track/stage3/P3 \"\xc3\xa9\" \\ \xc3\xb1");
    char *kml = slurp(dir, "mission.kml");
    CHECK(kml != NULL && strstr(kml, "<name>paper &amp; &lt;test&gt; &quot;case&quot; "
                                     "&apos;x&apos;</name>") != NULL);
    CHECK(kml != NULL && strstr(kml, "<name>stage1: P4, &lt;&amp;&gt; &quot;q&quot; "
                                     "&apos;s&apos;</name>") != NULL);
    free(kml);
}

/* Line of `text` that starts with `prefix`, as a fresh string (up to its newline), or NULL. */
static char *line_of(const char *text, const char *prefix)
{
    for (const char *p = text; p != NULL && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL)
        if (strncmp(p, prefix, strlen(prefix)) == 0) {
            const size_t n = strchr(p, '\n') ? (size_t)(strchr(p, '\n') - p) : strlen(p);
            char *l = malloc(n + 1);
            memcpy(l, p, n);
            l[n] = '\0';
            return l;
        }
    return NULL;
}

static int has_line(const char *text, const char *prefix)
{
    char *l = text ? line_of(text, prefix) : NULL;
    free(l);
    return l != NULL;
}

static size_t count_of(const char *text, const char *what)
{
    size_t n = 0;
    for (const char *p = text; p != NULL && (p = strstr(p, what)) != NULL; p += strlen(what))
        n++;
    return n;
}

/* A coast across the leap second 2016-12-31T23:59:60Z (tests/missions/leap_second.yaml: epoch
 * 23:55:00 UTC, rows every 0.5 s to t = 600 s). The answers follow from the IERS list alone:
 * t = 300 s is 23:59:60 (the leap second), t = 301 s is 2017-01-01T00:00:00 and t = 600 s is
 * 00:04:59, one second before epoch + t without the leap second (00:00:01, 00:05:00). */
static void test_leap_second(void)
{
    const char *dir = "export_out/leap";
    if (run_mission("tests/missions/leap_second.yaml", dir) != 0)
        return;
    lv_err err = {0};
    lv_export_report rep;
    CHECK_OK(lv_export_run_report(dir, LV_EXPORT_ALL, &rep, &err), &err);
    int kml_note = 0;
    for (size_t i = 0; i < rep.n; i++)
        kml_note |= strcmp(rep.items[i].format, "kml") == 0 &&
                    strstr(rep.items[i].note, "inside a leap second written as "
                                              "23:59:59.999999") != NULL;
    CHECK(kml_note);
    lv_export_report_clear(&rep);

    /* OEM (CCSDS 502.0-B-2; time code A of 301.0-B-4 has a second 60): the rows around the
     * leap second, the phase boundary at t = 400 s and the last row */
    char *oem = slurp(dir, "sat.oem");
    CHECK(oem != NULL);
    CHECK(has_line(oem, "2016-12-31T23:59:59.500000 "));                      /* t = 299.5 */
    CHECK(has_line(oem, "2016-12-31T23:59:60 "));                             /* t = 300 */
    CHECK(has_line(oem, "2016-12-31T23:59:60.500000 "));                      /* t = 300.5 */
    CHECK(has_line(oem, "2017-01-01T00:00:00 "));                             /* t = 301 */
    CHECK(has_line(oem, "2017-01-01T00:01:39 "));                             /* t = 400 */
    CHECK(has_line(oem, "2017-01-01T00:04:59 "));                             /* t = 600 */
    CHECK(!has_line(oem, "2017-01-01T00:05:00 "));
    CHECK(has_line(oem, "STOP_TIME = 2017-01-01T00:04:59"));
    CHECK(has_line(oem, "COMMENT leap second 2016-12-31T23:59:60 inside the span: TAI - UTC "
                        "36 s before, 37 s after"));
    /* the row at t = 301 s is the one 2 s after t = 299 s: the same position as the CSV's */
    char *csv = slurp(dir, "body_sat.csv");
    CHECK(csv != NULL && has_line(csv, "301,coast,"));
    free(csv);
    free(oem);
    {   /* the OEM is ASCII (CCSDS 502.0-B-2, 7.2): a mission named in UTF-8 (u umlaut, the
         * two CJK letters of "rocket", a rocket emoji) has each character written as '_' */
        const char *u8 = "export_out/leap_utf8";
        mkdir(u8, 0777);
        copy_file(dir, u8, "summary.json");
        copy_file(dir, u8, "body_sat.csv");
        replace_in(u8, "summary.json", "\"leap-second\"",
                   "\"l\xc3\xbcp \xe7\x81\xab\xe7\xae\xad \xf0\x9f\x9a\x80\"");
        CHECK_OK(lv_export_run(u8, LV_EXPORT_OEM, &err), &err);
        char *o8 = slurp(u8, "sat.oem");
        CHECK(o8 != NULL && has_line(o8, "OBJECT_ID = l_p __ _/sat"));
        int ascii = o8 != NULL;
        for (const char *q = o8; q != NULL && *q; q++)
            ascii &= (unsigned char)*q < 0x80;
        CHECK(ascii);
        free(o8);
    }

    /* KML: xsd:dateTime has no second 60, so the leap second's rows are one <when>,
     * 23:59:59.999999Z (the first of them kept); after it the same 1 s shift as the OEM */
    char *kml = slurp(dir, "mission.kml");
    CHECK(kml != NULL);
    CHECK(count_of(kml, "<when>2016-12-31T23:59:59.999999Z</when>") == 1);
    CHECK(count_of(kml, "<when>2016-12-31T23:59:59.500000Z</when>") == 1);
    CHECK(count_of(kml, "<when>2017-01-01T00:00:00Z</when>") == 1);
    CHECK(count_of(kml, "<when>2017-01-01T00:04:59Z</when>") == 1);
    CHECK(count_of(kml, "23:59:60") == 1); /* only in the description, as text */
    CHECK(count_of(kml, "00:05:00") == 0);
    CHECK(count_of(kml, "<begin>2017-01-01T00:01:39Z</begin><end>2017-01-01T00:04:59Z</end>") == 1);
    free(kml);

    /* CZML: Cesium's JulianDate reads the epoch (and intervals) as UTC with leap seconds and
     * adds the samples' seconds on the TAI scale: the epoch and the SI-second offsets as they
     * are, the intervals' ends shifted like the OEM's */
    check_czml(dir, 2, "2016-12-31T23:55:00Z/2017-01-01T00:04:59Z");
    char *czml = slurp(dir, "mission.czml");
    cJSON *doc = czml ? cJSON_Parse(czml) : NULL;
    free(czml);
    const cJSON *tr = cJSON_GetArrayItem(doc, 2); /* track/sat/coast2 */
    const cJSON *pos = cJSON_GetObjectItem(tr, "position");
    CHECK(strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(tr, "id")), "track/sat/coast2") == 0);
    CHECK(strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(pos, "epoch")),
                 "2016-12-31T23:55:00Z") == 0);
    const cJSON *smp = cJSON_GetObjectItem(pos, "cartographicDegrees");
    CHECK(cJSON_GetArraySize(smp) > 4);
    CHECK_CLOSE(cJSON_GetArrayItem(smp, 0)->valuedouble, 400.0, 0.0);
    int marker = 0; /* coast2's start marker: from t = 400 s (00:01:39, not 00:01:40) on */
    const cJSON *p;
    cJSON_ArrayForEach(p, doc)
    {
        const char *id = cJSON_GetStringValue(cJSON_GetObjectItem(p, "id"));
        const char *av = cJSON_GetStringValue(cJSON_GetObjectItem(p, "availability"));
        marker += id != NULL && strcmp(id, "event/coast2/0") == 0 && av != NULL &&
                  strcmp(av, "2017-01-01T00:01:39Z/2017-01-01T00:04:59Z") == 0;
    }
    CHECK(marker == 1);
    cJSON_Delete(doc);

    /* summary.json: the same instants and the leap second at t = 300 s */
    char *text = slurp(dir, "summary.json");
    cJSON *sum = text ? cJSON_Parse(text) : NULL;
    free(text);
    const cJSON *tm = cJSON_GetObjectItem(sum, "time");
    CHECK(strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(sum, "epoch")),
                 "2016-12-31T23:55:00Z") == 0);
    CHECK_CLOSE(cJSON_GetNumberValue(cJSON_GetObjectItem(tm, "tai_minus_utc")), 36.0, 0.0);
    CHECK(strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(tm, "start")),
                 "2016-12-31T23:55:00Z") == 0);
    CHECK(strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(tm, "end")),
                 "2017-01-01T00:04:59Z") == 0);
    const cJSON *leaps = cJSON_GetObjectItem(tm, "leap_seconds");
    CHECK(cJSON_GetArraySize(leaps) == 1);
    const cJSON *l0 = cJSON_GetArrayItem(leaps, 0);
    CHECK(strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(l0, "utc")), "2016-12-31T23:59:60Z") ==
          0);
    CHECK_CLOSE(cJSON_GetNumberValue(cJSON_GetObjectItem(l0, "t")), 300.0, 0.0);
    CHECK(cJSON_GetObjectItem(tm, "note") == NULL); /* 2016 is inside ERFA's table */
    CHECK_CLOSE(mission_end(dir), 600.0, 1e-9);
    cJSON_Delete(sum);

    /* An epoch inside the leap second (edited into a copy of the summary): t = 0.5 s is
     * 23:59:60.5, t = 1 s the new year; a second 60 where there was none is refused. */
    const char *at60 = "export_out/leap60";
    mkdir(at60, 0777);
    copy_file(dir, at60, "summary.json");
    copy_file(dir, at60, "body_sat.csv");
    replace_in(at60, "summary.json", "\"2016-12-31T23:55:00Z\"", "\"2016-12-31T23:59:60Z\"");
    CHECK_OK(lv_export_run(at60, LV_EXPORT_OEM, &err), &err);
    oem = slurp(at60, "sat.oem");
    CHECK(oem != NULL && has_line(oem, "START_TIME = 2016-12-31T23:59:60"));
    CHECK(oem != NULL && has_line(oem, "2016-12-31T23:59:60.500000 "));
    CHECK(oem != NULL && has_line(oem, "2017-01-01T00:00:00 "));
    CHECK(oem != NULL && has_line(oem, "2017-01-01T00:09:59 ")); /* t = 600 s */
    free(oem);
    replace_in(at60, "summary.json", "\"2016-12-31T23:59:60Z\"", "\"2016-12-30T23:59:60Z\"");
    CHECK_FAILS(lv_export_run(at60, LV_EXPORT_OEM, &err), &err, LV_ERR_INPUT,
                "export_out/leap60/summary.json: epoch '2016-12-30T23:59:60Z': no leap second");

    /* Past ERFA's table (its dubious years: five after its release): said, not hidden */
    replace_in(at60, "summary.json", "\"2016-12-30T23:59:60Z\"", "\"2200-06-30T23:55:00Z\"");
    CHECK_OK(lv_export_run_report(at60, LV_EXPORT_ALL, &rep, &err), &err);
    int utc_note = 0;
    for (size_t i = 0; i < rep.n; i++)
        utc_note |= strcmp(rep.items[i].format, "utc") == 0 && rep.items[i].file[0] == '\0' &&
                    strstr(rep.items[i].note, "leap-second table") != NULL;
    CHECK(utc_note);
    lv_export_report_clear(&rep);
    oem = slurp(at60, "sat.oem");
    CHECK(oem != NULL && has_line(oem, "COMMENT UTC from "));
    free(oem);
    /* ... and past the year 9999, which the text cannot hold: refused (t = 600 s is 10000) */
    replace_in(at60, "summary.json", "\"2200-06-30T23:55:00Z\"", "\"9999-12-31T23:55:00Z\"");
    CHECK_FAILS(lv_export_run(at60, LV_EXPORT_CZML, &err), &err, LV_ERR_INPUT,
                "leave the years 0000-9999");
}

/* The contract of every registered export (export.c's table): a name of at most 7 lowercase
 * letters or digits, unique (the words of --format and --outputs); flag 1u << position (the
 * public LV_EXPORT_* agree); lv_export_format_info says the same; exported alone from the dof3
 * results folder (every export has something to write there) it reports under its own name
 * only, and each file it reports exists and matches its `pattern`, which outdir.c uses to
 * tell lvsim's files from the user's. */
static void check_registry(const char *dir)
{
    const size_t n = lv_ex_format_count();
    CHECK(n >= 3 && lv_export_format_info(n, NULL, NULL) == NULL);
    CHECK(strcmp(lv_ex_formats[0]->name, "czml") == 0 && LV_EXPORT_CZML == 1u << 0);
    CHECK(strcmp(lv_ex_formats[1]->name, "kml") == 0 && LV_EXPORT_KML == 1u << 1);
    CHECK(strcmp(lv_ex_formats[2]->name, "oem") == 0 && LV_EXPORT_OEM == 1u << 2);
    for (size_t i = 0; i < n; i++) {
        const lv_ex_format *f = lv_ex_formats[i];
        const char *files = NULL, *desc = NULL;
        CHECK(lv_export_format_info(i, &files, &desc) == f->name && files == f->files &&
              desc == f->description);
        const size_t len = strlen(f->name);
        CHECK(len >= 1 && len < sizeof ((lv_export_item *)0)->format &&
              strspn(f->name, "abcdefghijklmnopqrstuvwxyz0123456789") == len);
        CHECK(f->pattern != NULL && f->files != NULL && f->write != NULL && desc[0] != '\0');
        for (size_t j = 0; j < i; j++)
            CHECK(strcmp(f->name, lv_ex_formats[j]->name) != 0);
        lv_export_report rep;
        lv_err err = {0};
        CHECK_OK(lv_export_run_report(dir, 1u << i, &rep, &err), &err);
        size_t written = 0;
        for (size_t k = 0; k < rep.n; k++) {
            const lv_export_item *it = &rep.items[k];
            CHECK(strcmp(it->format, f->name) == 0 || strcmp(it->format, "utc") == 0);
            if (it->file[0] == '\0')
                continue;
            written++;
            CHECK(exists(dir, it->file) && fnmatch(f->pattern, it->file, 0) == 0);
        }
        if (written == 0)
            fprintf(stderr, "export '%s' wrote nothing into %s\n", f->name, dir);
        CHECK(written > 0);
        lv_export_report_clear(&rep);
    }
    lv_err err = {0};
    CHECK_FAILS(lv_export_run(dir, 1u << n, &err), &err, LV_ERR_INPUT, "unknown format flag");
}

int main(void)
{
    lv_err err = {0};
    mkdir("export_out", 0777);

    /* Paper test case: flat world, 3 bodies over 5 phases; no OEM (not orbital). */
    const char *paper = "export_out/paper";
    if (run_mission("examples/paper-test-case/mission.yaml", paper) == 0) {
        CHECK_OK(lv_export_run(paper, LV_EXPORT_ALL, &err), &err);
        CHECK(exists(paper, "mission.czml"));
        CHECK(exists(paper, "mission.kml"));
        CHECK(!exists(paper, "stage1.oem") && !exists(paper, "stage3.oem"));
        CHECK(!exists(paper, "mission.czml.tmp") && !exists(paper, "mission.kml.tmp"));
        /* stage1: P1 P4, stage2: P1 P2 P5, stage3: P1 P2 P3; P5 ends by impact at the latest
         * time: 12:18:09.078 */
        char iv[100];
        const double t1 = mission_end(paper);
        CHECK_CLOSE(t1, 1089.0782, 0.01);
        mission_interval(t1, iv, sizeof iv);
        check_czml(paper, 8, iv);
        check_czml_layout(paper, NULL);
        names_folder(paper);
    }

    /* dof3 branch: rotating Earth; the upper stage and the core (apogee ~230 km) both fly
     * above 100 km, but only the upper stage's conic clears the Earth (it escapes): one OEM;
     * the core's ballistic arc (it impacts at 663.9018142 s, the mission's end) has none. */
    const char *dof3 = "export_out/dof3";
    if (run_mission("examples/dof3-branch/mission.yaml", dof3) == 0) {
        CHECK_OK(lv_export_run(dof3, LV_EXPORT_ALL, &err), &err);
        CHECK(exists(dof3, "mission.czml"));
        CHECK(exists(dof3, "mission.kml"));
        CHECK(exists(dof3, "upper.oem"));
        CHECK(!exists(dof3, "core.oem"));
        check_registry(dof3);
        char iv[100];
        const double t1 = mission_end(dof3);
        CHECK_CLOSE(t1, 663.9018, 0.01);
        mission_interval(t1, iv, sizeof iv);
        check_czml(dof3, 4, iv);
        check_czml_layout(dof3, NULL);
        /* One format alone, rewritten in place. */
        CHECK_OK(lv_export_run(dof3, LV_EXPORT_OEM, &err), &err);
        CHECK(!exists(dof3, "upper.oem.tmp"));
        /* a core.oem of an earlier export (lvsim's first lines) contradicts the rule: removed;
         * a file of the same name that is not lvsim's stays */
        static const char *const heads[2] = {"CCSDS_OEM_VERS = 2.0\nCOMMENT lvsim 0.9 old\n",
                                             "my own notes\n"};
        for (int k = 0; k < 2; k++) {
            char path[512];
            snprintf(path, sizeof path, "%s/core.oem", dof3);
            FILE *f = fopen(path, "w");
            CHECK(f != NULL);
            if (f != NULL) {
                fputs(heads[k], f);
                fclose(f);
            }
            CHECK_OK(lv_export_run(dof3, LV_EXPORT_OEM, &err), &err);
            CHECK(exists(dof3, "core.oem") == (k == 1));
        }
        remove("export_out/dof3/core.oem");
    }

    test_leap_second();
    test_json_numbers();
    test_clock();

    /* Errors: no summary.json (the path is named); unknown flags. */
    mkdir("export_out/empty", 0777);
    CHECK_FAILS(lv_export_run("export_out/empty", LV_EXPORT_ALL, &err), &err, LV_ERR_IO,
                "export_out/empty/summary.json");
    CHECK_FAILS(lv_export_run(paper, 64u, &err), &err, LV_ERR_INPUT, "flag");
    CHECK(lv_export_run("export_out/empty", LV_EXPORT_CZML, NULL) == LV_ERR_IO);

    /* A copy of the paper folder with broken files: the CSV error names file:line. */
    const char *bad = "export_out/bad";
    mkdir(bad, 0777);
    const char *files[] = {"summary.json", "body_stage1.csv", "body_stage2.csv",
                           "body_stage3.csv"};
    for (int i = 0; i < 4; i++)
        copy_file(paper, bad, files[i]);
    {
        char *csv = slurp(bad, "body_stage2.csv"); /* line 5: its time becomes "1.5x" */
        char *p = csv;
        for (int line = 1; p != NULL && line < 5; line++)
            p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL;
        CHECK(p != NULL);
        if (p != NULL) {
            char *comma = strchr(p, ',');
            FILE *f = fopen("export_out/bad/body_stage2.csv", "wb");
            fwrite(csv, 1, (size_t)(p - csv), f);
            fputs("1.5x", f);
            fputs(comma, f);
            fclose(f);
        }
        free(csv);
    }
    CHECK_FAILS(lv_export_run(bad, LV_EXPORT_KML, &err), &err, LV_ERR_INPUT,
                "export_out/bad/body_stage2.csv:5:");
    CHECK(!exists(bad, "mission.kml"));
    /* Too few fields on line 3 of stage 3's CSV. */
    {
        FILE *f = fopen("export_out/bad/body_stage2.csv", "wb");
        fclose(f);
        copy_file(paper, bad, "body_stage2.csv");
        char *csv = slurp(bad, "body_stage3.csv");
        char *l3 = strchr(strchr(csv, '\n') + 1, '\n') + 1;
        *strchr(l3, ',') = '\n'; /* "t\nphase,...": line 3 has one field */
        f = fopen("export_out/bad/body_stage3.csv", "wb");
        fputs(csv, f);
        fclose(f);
        free(csv);
    }
    CHECK_FAILS(lv_export_run(bad, LV_EXPORT_CZML, &err), &err, LV_ERR_INPUT,
                "export_out/bad/body_stage3.csv:3: 1 fields");
    /* A summary that is not JSON: file and line. */
    {
        copy_file(paper, bad, "body_stage3.csv");
        FILE *f = fopen("export_out/bad/summary.json", "wb");
        fputs("{\n  \"mission\": \"x\",\n  \"epoch\": oops\n}\n", f);
        fclose(f);
    }
    CHECK_FAILS(lv_export_run(bad, LV_EXPORT_CZML, &err), &err, LV_ERR_INPUT,
                "export_out/bad/summary.json:3: malformed JSON");
    /* A missing body CSV: LV_ERR_IO naming it. */
    copy_file(paper, bad, "summary.json");
    remove("export_out/bad/body_stage1.csv");
    CHECK_FAILS(lv_export_run(bad, LV_EXPORT_CZML, &err), &err, LV_ERR_IO,
                "export_out/bad/body_stage1.csv");

    return check_report("test_export");
}
