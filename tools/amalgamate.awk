# SPDX-License-Identifier: MIT
# tools/amalgamate.awk - the body of tools/amalgamate.sh (read its comment).
function norm(p,    n, i, k, part, res) { # collapse "a/b/../c" and "./"
    n = split(p, part, "/"); k = 0
    for (i = 1; i <= n; i++) {
        if (part[i] == "." || part[i] == "") continue
        if (part[i] == ".." && k > 0 && res[k] != "..") { k--; continue }
        res[++k] = part[i]
    }
    p = ""
    for (i = 1; i <= k; i++) p = p (i > 1 ? "/" : "") res[i]
    return p
}
function dirof(p) { return (p ~ /\//) ? substr(p, 1, match(p, /\/[^\/]*$/) - 1) : "." }
function exists(p,    line, r) { r = (getline line < p); if (r >= 0) close(p); return r >= 0 }
function resolve(name, from,    p) {
    p = norm(dirof(from) "/" name); if (exists(p)) return p
    p = norm("src/" name); if (exists(p)) return p
    return ""
}
# Copy file f to dst, inlining internal headers once.  is_c: f is a .c file.
function emit(f, dst, is_c,    line, n, depth, name, p, r) {
    done[f] = 1
    if (lines) print "#line 1 \"" f "\"" > dst
    n = 0; depth = 0
    while ((r = (getline line < f)) > 0) {
        n++
        if (line ~ /^[ \t]*#[ \t]*if/) depth++
        else if (line ~ /^[ \t]*#[ \t]*endif/) depth--
        if (is_c && line ~ /^[ \t]*#[ \t]*define[ \t]/) {
            name = line; sub(/^[ \t]*#[ \t]*define[ \t]+/, "", name); sub(/[^A-Za-z0-9_].*$/, "", name)
            macros[f] = macros[f] " " name
        }
        if (line ~ /^[ \t]*#[ \t]*include[ \t]*"/) {
            name = line; sub(/^[^"]*"/, "", name); sub(/".*$/, "", name)
            p = resolve(name, f)
            if (p == "") { printf "amalgamate: %s:%d: cannot find \"%s\"\n", f, n, name > "/dev/stderr"; exit 1 }
            if (p in done) print "" > dst # keeps the line numbers
            else if (depth > (is_c ? 0 : 1)) {
                printf "amalgamate: %s:%d: \"%s\" is included under #if; it would be inlined only once\n", f, n, name > "/dev/stderr"
                exit 1
            } else {
                emit(p, dst, 0)
                if (lines) print "#line " (n + 1) " \"" f "\"" > dst
            }
        } else if (line ~ /^[ \t]*#[ \t]*include[ \t]*</ && depth <= (is_c ? 0 : 1)) {
            name = line; sub(/^[^<]*</, "", name); sub(/>.*$/, "", name)
            print ((dst SUBSEP name) in sys ? "" : line) > dst # once per output
            sys[dst, name] = 1
        } else print line > dst
        if (is_c && n == lastinc[f]) define_renames(f, n, dst)
    }
    if (r < 0) { printf "amalgamate: cannot read %s\n", f > "/dev/stderr"; exit 1 }
    close(f)
}
function define_renames(f, n, dst,    nr, rn, k) {
    nr = split(renames[f], rn, " ")
    for (k = 1; k <= nr; k++) print "#define " rn[k] " " renamed(f, rn[k]) > dst
    if (nr && lines) print "#line " (n + 1) " \"" f "\"" > dst
}
# Identifiers of file f, comments and string literals left out: ntok[name]
# counts the .c files that use a name, users[name] lists them.
function tokens(f,    line, rest, t, incom, got, i, n, w) {
    incom = 0; split("", got)
    while ((getline line < f) > 0) {
        rest = ""
        while (line != "") {
            if (incom) {
                i = index(line, "*/"); if (!i) { line = ""; break }
                line = substr(line, i + 2); incom = 0; continue
            }
            if (match(line, /\/\*|\/\/|"|'/) == 0) { rest = rest " " line; break }
            rest = rest " " substr(line, 1, RSTART - 1); t = substr(line, RSTART, RLENGTH)
            line = substr(line, RSTART + RLENGTH)
            if (t == "//") break
            if (t == "/*") { incom = 1; continue }
            # a string or character literal: skip to its unescaped end
            while (match(line, "\\\\.|" t) && substr(line, RSTART, 1) == "\\") line = substr(line, RSTART + RLENGTH)
            line = match(line, t) ? substr(line, RSTART + 1) : ""
        }
        n = split(rest, w, /[^A-Za-z0-9_]+/)
        for (i = 1; i <= n; i++) if (w[i] ~ /^[A-Za-z_]/ && !(w[i] in got)) { got[w[i]] = 1; ntok[w[i]]++; users[w[i]] = users[w[i]] " " f }
    }
    close(f)
}
# Names a .c file defines at file scope (lines that start in column 0 with
# static, typedef, struct/union/enum or "} name;"), and the line of its last
# include: the renames go after it, so no header is inlined under them.
function defs(f,    line, name, n, d) {
    n = 0; d = 0
    while ((getline line < f) > 0) {
        n++
        if (line ~ /^[ \t]*#[ \t]*if/) d++
        else if (line ~ /^[ \t]*#[ \t]*endif/) d--
        if (d == 0 && line ~ /^[ \t]*#[ \t]*include/) lastinc[f] = n
        name = ""
        sub(/[ \t]*\/\/.*$/, "", line); sub(/[ \t]*\/\*.*\*\/[ \t]*$/, "", line)
        while (line ~ /\{[^{}]*\}/) gsub(/\{[^{}]*\}/, "", line) # struct bodies, one-line functions
        if (line ~ /^(typedef[ \t]+)?(struct|union|enum)[ \t]+[A-Za-z_]/) {
            name = line; sub(/^(typedef[ \t]+)?(struct|union|enum)[ \t]+/, "", name); sub(/[^A-Za-z0-9_].*$/, "", name); def(f, name)
        }
        if (line ~ /^typedef[ \t].*\(\*[ \t]*[A-Za-z_]/) { name = line; sub(/^[^(]*\(\*[ \t]*/, "", name); sub(/[^A-Za-z0-9_].*$/, "", name) }
        else if (line ~ /^typedef[ \t].*;[ \t]*$/ || line ~ /^}[ \t]*[A-Za-z_][A-Za-z0-9_]*[ \t]*;/) { name = line; sub(/[ \t]*;[ \t]*$/, "", name); sub(/^.*[^A-Za-z0-9_]/, "", name) }
        else if (line ~ /^static[ \t]/) { name = line; sub(/[(\[=;].*$/, "", name); sub(/[ \t*]+$/, "", name); sub(/^.*[^A-Za-z0-9_]/, "", name) }
        def(f, name)
    }
    close(f)
}
function def(f, name) {
    if (name == "" || name in keyword || (f SUBSEP name) in defined) return
    defined[f, name] = 1; defs_of[f] = defs_of[f] " " name; definers[name] = definers[name] " " f
}
function renamed(f, name,    id) { id = f; sub(/^src\//, "", id); sub(/\.c$/, "", id); gsub(/[^A-Za-z0-9]/, "_", id); return "tgi_" id "_" name }
# A file-scope name of f that another .c file uses too (a second definition,
# or a local that would shadow it) is renamed in f.
function plan_renames(f,    n, k, names, others) {
    n = split(defs_of[f], names, " ")
    for (k = 1; k <= n; k++) {
        if (ntok[names[k]] < 2) continue
        renames[f] = renames[f] " " names[k]
        others = users[names[k]]; sub(" " f, "", others)
        nrenamed++
        if (!verbose) continue
        if (definers[names[k]] != " " f) { if (!(names[k] in told)) printf "amalgamate: %s is defined in%s: renamed in each file\n", names[k], definers[names[k]] > "/dev/stderr"; told[names[k]] = 1 }
        else printf "amalgamate: %s (%s) is also used in%s: renamed %s\n", names[k], f, others, renamed(f, names[k]) > "/dev/stderr"
    }
}
BEGIN {
    split("auto break case char const continue default do double else enum extern float for goto if inline int long register restrict return short signed sizeof static struct switch typedef union unsigned void volatile while", kw, " ")
    for (i in kw) keyword[kw[i]] = 1
    hdr = out "/tinygi.h"; src = out "/tinygi.c"; scene_hdr = out "/tinygi_scene.h"
    head = "/* SPDX-License-Identifier: MIT */\n/* tinygi " version " - generated by tools/amalgamate.sh from src/; do not edit. */\n"
    printf "%s", head > hdr
    emit("src/tinygi.h", hdr, 0)
    close(hdr)
    # tinygi_scene.h, for baked scenes: the scene's tables with the core
    # headers they need inlined, on top of tinygi.h (which it includes);
    # what it inlines is inlined again in tinygi.c (another file)
    for (k in done) kept[k] = 1
    printf "%s", head > scene_hdr
    print "#include \"tinygi.h\"" > scene_hdr
    emit("src/tinygi_scene.h", scene_hdr, 0)
    close(scene_hdr)
    delete done
    for (k in kept) done[k] = 1

    for (i = 1; i < ARGC; i++) { tokens(ARGV[i]); defs(ARGV[i]) }
    for (i = 1; i < ARGC; i++) plan_renames(ARGV[i])
    if (nrenamed && !verbose)
        printf "amalgamate: %d file-scope names renamed to share one translation unit (AMALGAMATE_VERBOSE=1 lists them)\n", nrenamed > "/dev/stderr"
    lines = 1 # the header goes to users: no #line pointing into src/
    printf "%s", head > src
    print "/* Build: cc -std=c99 -O2 -c tinygi.c (add -DTG_FIXED=1 for Q16.16 fixed point;\n   -ffp-contract=off, and with gcc -fexcess-precision=fast, give the same bits on every target). */" > src
    print "#if defined(__clang__) /* the inlined headers' unused static inline functions, as in separate files */" > src
    print "#pragma clang diagnostic ignored \"-Wunused-function\"" > src
    print "#endif" > src
    print "#include \"tinygi.h\"" > src
    for (i = 1; i < ARGC; i++) {
        f = ARGV[i]
        emit(f, src, 1)
        nm = split(macros[f] renames[f], names, " ")
        for (k = 1; k <= nm; k++) if (!((f SUBSEP names[k]) in undone)) { undone[f, names[k]] = 1; print "#undef " names[k] > src }
    }
    close(src)
    exit 0
}
