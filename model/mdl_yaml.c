/* The YAML document of a model file as an immutable tree with positions (see mdl_yaml.h).
 *
 * Method: libyaml's event parser (yaml_parser_parse) drives a stack of open collections; a node
 * is complete at its scalar event or at the end event of its collection, and is then appended to
 * the collection below it (or becomes the root). The event API, rather than the document API,
 * lets the limits act while the input is read: the depth of the stack, and a running count of
 * the nodes the document expands to (an alias counts with the whole subtree it stands for), so a
 * "billion laughs" is stopped at the alias that crosses the budget, before anything is built.
 *
 * Memory: the document owns an arena (a list of blocks) that holds every node, child array and
 * string; freeing the document frees the blocks. Two hash tables (open addressing, FNV-1a) live
 * only while loading: the anchors (name -> node), and the keys of all mappings (mapping serial,
 * key text) -> key node, which finds a duplicate key in O(1) as it is read.
 *
 * Invariants: an anchor is registered only once its node is complete, so an alias can never
 * refer to a collection that encloses it (the tree is acyclic); the expanded count never exceeds
 * MDL_Y_MAX_NODES, so every weight fits in a long. */
#include "mdl_yaml.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

/* ---- the arena ---- */

typedef struct block {
    struct block *next;
    size_t used, size;
    _Alignas(16) unsigned char data[];
} block;

struct mdl_y_doc {
    block *blocks;
    const mdl_y_node *root;
    char *file;
};

static void *arena_alloc(mdl_y_doc *d, size_t size)
{
    size = (size + 15) & ~(size_t)15;
    block *b = d->blocks;
    if (!b || b->size - b->used < size) {
        size_t bs = size > 65536 ? size : 65536;
        b = malloc(sizeof *b + bs);
        if (!b) return NULL;
        b->size = bs;
        b->used = 0;
        b->next = d->blocks;
        d->blocks = b;
    }
    void *p = b->data + b->used;
    b->used += size;
    return p;
}

static char *arena_strdup(mdl_y_doc *d, const char *s, size_t len)
{
    char *c = arena_alloc(d, len + 1);
    if (c) {
        memcpy(c, s, len);
        c[len] = '\0';
    }
    return c;
}

/* A node with its expanded size (itself and all it holds, aliases expanded). */
typedef struct inode {
    mdl_y_node pub; /* first: a mdl_y_node * of this module is an inode * */
    long weight;
} inode;

/* ---- hash table of (tag, text) -> node ---- */

typedef struct hentry {
    unsigned long tag; /* 0: unused slot; mapping serial or 1 for anchors */
    const char *s;
    size_t len;
    const inode *val;
} hentry;

typedef struct htab {
    hentry *e;
    size_t cap, n;
} htab;

static size_t hash(unsigned long tag, const char *s, size_t len)
{
    unsigned long long h = 1469598103934665603ull ^ tag;
    for (size_t i = 0; i < len; i++)
        h = (h ^ (unsigned char)s[i]) * 1099511628211ull;
    return (size_t)(h ^ (h >> 29));
}

/* The entry of (tag, s): found (*found = 1) or a new one with val NULL; NULL without memory. */
static hentry *h_lookup(htab *h, unsigned long tag, const char *s, size_t len, int *found)
{
    if ((h->n + 1) * 2 > h->cap) {
        size_t cap = h->cap ? 2 * h->cap : 64;
        hentry *e = calloc(cap, sizeof *e);
        if (!e) return NULL;
        for (size_t i = 0; i < h->cap; i++) {
            if (!h->e[i].tag) continue;
            size_t j = hash(h->e[i].tag, h->e[i].s, h->e[i].len) & (cap - 1);
            while (e[j].tag)
                j = (j + 1) & (cap - 1);
            e[j] = h->e[i];
        }
        free(h->e);
        h->e = e;
        h->cap = cap;
    }
    size_t j = hash(tag, s, len) & (h->cap - 1);
    for (; h->e[j].tag; j = (j + 1) & (h->cap - 1))
        if (h->e[j].tag == tag && h->e[j].len == len && !memcmp(h->e[j].s, s, len)) {
            *found = 1;
            return &h->e[j];
        }
    *found = 0;
    h->e[j] = (hentry){tag, s, len, NULL};
    h->n++;
    return &h->e[j];
}

/* ---- the loader ---- */

typedef struct frame {
    inode *node;
    const inode **kids; /* items, or keys and values alternately */
    int nk, kcap;
    long count0;        /* the expanded count before the collection */
    const char *anchor; /* in the arena, or NULL */
    unsigned long serial;
} frame;

typedef struct loader {
    mdl_y_doc *doc;
    const unsigned char *input;
    size_t len;
    frame stack[MDL_Y_MAX_DEPTH];
    int depth;
    long count; /* nodes so far, aliases expanded */
    unsigned long serial;
    htab anchors, keys;
    int ndocs;
    mdl_y_error *e;
} loader;

static int lfail(loader *L, int line, int column, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int lfail(loader *L, int line, int column, const char *fmt, ...)
{
    if (!L->e) return -1;
    char *m = L->e->message;
    size_t size = sizeof L->e->message;
    int k = line > 0 ? snprintf(m, size, "%s:%d:%d: ", L->doc->file, line, column)
                     : snprintf(m, size, "%s: ", L->doc->file);
    if (k < 0) k = 0;
    if ((size_t)k >= size) k = (int)size - 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(m + k, size - (size_t)k, fmt, ap);
    va_end(ap);
    L->e->line = line;
    L->e->column = column;
    return -1;
}

static int mfail(loader *L, yaml_mark_t m, const char *msg)
{
    return lfail(L, (int)m.line + 1, (int)m.column + 1, "%s", msg);
}

/* Text for a message: at most 60 bytes of s, cut with "...". */
static const char *shorten(const char *s, size_t len, char *buf, size_t size)
{
    if (len > 60)
        snprintf(buf, size, "%.57s...", s);
    else
        snprintf(buf, size, "%.*s", (int)len, s);
    return buf;
}

/* The line and column (1-based, counting characters) of byte offset off of the input. */
static void offset_position(const loader *L, size_t off, int *line, int *column)
{
    *line = 1;
    *column = 1;
    for (size_t i = 0; i < off && i < L->len; i++) {
        unsigned char c = L->input[i];
        if (c == '\n' || (c == '\r' && (i + 1 >= L->len || L->input[i + 1] != '\n'))) {
            ++*line;
            *column = 1;
        } else if ((c & 0xC0) != 0x80 && c != '\r') {
            ++*column;
        }
    }
}

static int parser_error(loader *L, const yaml_parser_t *p)
{
    int line, column;
    const char *problem = p->problem ? p->problem : "unknown problem";
    switch (p->error) {
    case YAML_MEMORY_ERROR:
        return lfail(L, 0, 0, "out of memory");
    case YAML_READER_ERROR:
        offset_position(L, p->problem_offset, &line, &column);
        if (p->problem_value != -1)
            return lfail(L, line, column, "%s (byte 0x%02X)", problem, (unsigned)p->problem_value);
        return lfail(L, line, column, "%s", problem);
    default:
        if (p->context)
            return lfail(L, (int)p->problem_mark.line + 1, (int)p->problem_mark.column + 1,
                         "%s (%s at line %d, column %d)", problem, p->context,
                         (int)p->context_mark.line + 1, (int)p->context_mark.column + 1);
        return lfail(L, (int)p->problem_mark.line + 1, (int)p->problem_mark.column + 1, "%s",
                     problem);
    }
}

/* Counts n more nodes of the expanded document. */
static int count_nodes(loader *L, long n, yaml_mark_t m)
{
    if (n > MDL_Y_MAX_NODES - L->count) {
        char msg[128];
        snprintf(msg, sizeof msg, "the document holds more than %d nodes with its aliases expanded",
                 MDL_Y_MAX_NODES);
        return mfail(L, m, msg);
    }
    L->count += n;
    return 0;
}

static inode *new_node(loader *L, mdl_y_kind kind, yaml_mark_t m)
{
    inode *n = arena_alloc(L->doc, sizeof *n);
    if (!n) {
        lfail(L, 0, 0, "out of memory");
        return NULL;
    }
    memset(n, 0, sizeof *n);
    n->pub.kind = kind;
    n->pub.file = L->doc->file;
    n->pub.line = (int)m.line + 1;
    n->pub.column = (int)m.column + 1;
    n->weight = 1;
    return n;
}

/* Checks a node's tag: none, the non-specific "!", or the standard one of its kind. */
static int check_tag(loader *L, const yaml_char_t *tag, const char *standard, yaml_mark_t m,
                     int *tagged)
{
    *tagged = 0;
    if (!tag) return 0;
    const char *t = (const char *)tag;
    if (!strcmp(t, "!") || !strcmp(t, standard)) {
        *tagged = 1;
        return 0;
    }
    char buf[72], msg[128];
    snprintf(msg, sizeof msg, "tags are not supported ('%s')",
             shorten(t, strlen(t), buf, sizeof buf));
    return mfail(L, m, msg);
}

static int register_anchor(loader *L, const char *anchor, const inode *n)
{
    if (!anchor) return 0;
    int found;
    hentry *h = h_lookup(&L->anchors, 1, anchor, strlen(anchor), &found);
    if (!h || (!found && !(h->s = arena_strdup(L->doc, anchor, strlen(anchor)))))
        return lfail(L, 0, 0, "out of memory");
    h->val = n; /* a later anchor of the same name replaces the earlier one */
    return 0;
}

/* Appends the complete node n to the open collection (or makes it the root). m: where it was
 * read (the alias for an alias). */
static int add_child(loader *L, const inode *n, yaml_mark_t m)
{
    if (L->depth == 0) {
        L->doc->root = &n->pub;
        return 0;
    }
    frame *f = &L->stack[L->depth - 1];
    if (f->node->pub.kind == MDL_Y_MAPPING && f->nk % 2 == 0) {
        char buf[72], msg[192];
        if (n->pub.kind != MDL_Y_SCALAR) {
            snprintf(msg, sizeof msg, "a mapping key must be a scalar, not a %s",
                     mdl_y_kind_name(n->pub.kind));
            return mfail(L, m, msg);
        }
        int found;
        hentry *h = h_lookup(&L->keys, f->serial, n->pub.text, n->pub.len, &found);
        if (!h) return lfail(L, 0, 0, "out of memory");
        if (found) {
            snprintf(msg, sizeof msg, "duplicate key '%s' (first at line %d)",
                     shorten(n->pub.text, n->pub.len, buf, sizeof buf), h->val->pub.line);
            return mfail(L, m, msg);
        }
        h->val = n;
    }
    if (f->nk == f->kcap) {
        int cap = f->kcap ? 2 * f->kcap : 8;
        const inode **k = realloc(f->kids, (size_t)cap * sizeof *k);
        if (!k) return lfail(L, 0, 0, "out of memory");
        f->kids = k;
        f->kcap = cap;
    }
    f->kids[f->nk++] = n;
    return 0;
}

static int on_scalar(loader *L, const yaml_event_t *ev)
{
    yaml_mark_t m = ev->start_mark;
    int tagged;
    if (check_tag(L, ev->data.scalar.tag, "tag:yaml.org,2002:str", m, &tagged) < 0) return -1;
    const char *v = (const char *)ev->data.scalar.value;
    size_t len = ev->data.scalar.length;
    if (memchr(v, 0, len)) return mfail(L, m, "a scalar holds a NUL character");
    if (count_nodes(L, 1, m) < 0) return -1;
    inode *n = new_node(L, MDL_Y_SCALAR, m);
    char *text = n ? arena_strdup(L->doc, v, len) : NULL;
    if (!text) return lfail(L, 0, 0, "out of memory");
    n->pub.text = text;
    n->pub.len = len;
    n->pub.quoted = tagged || ev->data.scalar.style != YAML_PLAIN_SCALAR_STYLE;
    if (register_anchor(L, (const char *)ev->data.scalar.anchor, n) < 0) return -1;
    return add_child(L, n, m);
}

static int on_start(loader *L, const yaml_event_t *ev, mdl_y_kind kind)
{
    yaml_mark_t m = ev->start_mark;
    int tagged;
    const yaml_char_t *tag =
        kind == MDL_Y_MAPPING ? ev->data.mapping_start.tag : ev->data.sequence_start.tag;
    const yaml_char_t *anchor =
        kind == MDL_Y_MAPPING ? ev->data.mapping_start.anchor : ev->data.sequence_start.anchor;
    if (check_tag(L, tag, kind == MDL_Y_MAPPING ? "tag:yaml.org,2002:map" : "tag:yaml.org,2002:seq",
                  m, &tagged) < 0)
        return -1;
    if (L->depth == MDL_Y_MAX_DEPTH) {
        char msg[96];
        snprintf(msg, sizeof msg, "collections nested too deeply (more than %d levels)",
                 MDL_Y_MAX_DEPTH);
        return mfail(L, m, msg);
    }
    long count0 = L->count;
    if (count_nodes(L, 1, m) < 0) return -1;
    inode *n = new_node(L, kind, m);
    const char *a = NULL;
    if (n && anchor) a = arena_strdup(L->doc, (const char *)anchor, strlen((const char *)anchor));
    if (!n || (anchor && !a)) return lfail(L, 0, 0, "out of memory");
    L->stack[L->depth++] = (frame){n, NULL, 0, 0, count0, a, ++L->serial};
    return 0;
}

static int on_end(loader *L)
{
    frame *f = &L->stack[L->depth - 1];
    inode *n = f->node;
    mdl_y_node *p = &n->pub;
    if (p->kind == MDL_Y_MAPPING) {
        p->n = f->nk / 2;
        mdl_y_pair *pairs = arena_alloc(L->doc, (size_t)(p->n ? p->n : 1) * sizeof *pairs);
        if (!pairs) return lfail(L, 0, 0, "out of memory");
        for (int i = 0; i < p->n; i++) {
            pairs[i].key = &f->kids[2 * i]->pub;
            pairs[i].value = &f->kids[2 * i + 1]->pub;
        }
        p->pairs = pairs;
    } else {
        p->n = f->nk;
        const mdl_y_node **items = arena_alloc(L->doc, (size_t)(p->n ? p->n : 1) * sizeof *items);
        if (!items) return lfail(L, 0, 0, "out of memory");
        for (int i = 0; i < p->n; i++)
            items[i] = &f->kids[i]->pub;
        p->items = items;
    }
    free(f->kids);
    f->kids = NULL;
    n->weight = L->count - f->count0;
    const char *anchor = f->anchor;
    yaml_mark_t m = {0, (size_t)p->line - 1, (size_t)p->column - 1};
    L->depth--;
    if (register_anchor(L, anchor, n) < 0) return -1;
    return add_child(L, n, m);
}

static int on_alias(loader *L, const yaml_event_t *ev)
{
    const char *a = (const char *)ev->data.alias.anchor;
    int found;
    hentry *h = h_lookup(&L->anchors, 1, a, strlen(a), &found);
    if (!h) return lfail(L, 0, 0, "out of memory");
    if (!found) {
        L->anchors.n--; /* drop the entry just made: tag 0 marks it unused again */
        h->tag = 0;
        char buf[72], msg[160];
        snprintf(msg, sizeof msg, "alias '*%s' refers to no anchor defined before it",
                 shorten(a, strlen(a), buf, sizeof buf));
        return mfail(L, ev->start_mark, msg);
    }
    if (count_nodes(L, h->val->weight, ev->start_mark) < 0) return -1;
    return add_child(L, h->val, ev->start_mark);
}

/* Reads the events up to the end of the stream into L->doc. */
static int load_events(loader *L)
{
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser)) return lfail(L, 0, 0, "out of memory");
    yaml_parser_set_input_string(&parser, L->input, L->len);
    int r = 0, done = 0;
    while (!done && r == 0) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&parser, &ev)) {
            r = parser_error(L, &parser);
            break;
        }
        switch (ev.type) {
        case YAML_DOCUMENT_START_EVENT:
            if (++L->ndocs > 1)
                r = mfail(L, ev.start_mark,
                          "a model file holds one YAML document; a second one starts here");
            break;
        case YAML_SCALAR_EVENT:
            r = on_scalar(L, &ev);
            break;
        case YAML_SEQUENCE_START_EVENT:
            r = on_start(L, &ev, MDL_Y_SEQUENCE);
            break;
        case YAML_MAPPING_START_EVENT:
            r = on_start(L, &ev, MDL_Y_MAPPING);
            break;
        case YAML_SEQUENCE_END_EVENT:
        case YAML_MAPPING_END_EVENT:
            r = on_end(L);
            break;
        case YAML_ALIAS_EVENT:
            r = on_alias(L, &ev);
            break;
        case YAML_STREAM_END_EVENT:
            done = 1;
            break;
        default:
            break;
        }
        yaml_event_delete(&ev);
    }
    yaml_parser_delete(&parser);
    return r;
}

void mdl_y_free(mdl_y_doc *doc)
{
    if (!doc) return;
    for (block *b = doc->blocks, *next; b; b = next) {
        next = b->next;
        free(b);
    }
    free(doc->file);
    free(doc);
}

int mdl_y_load_string(const char *text, size_t len, const char *name, mdl_y_doc **out,
                      mdl_y_error *e)
{
    if (out) *out = NULL;
    if (e) memset(e, 0, sizeof *e);
    if (!name) name = "<string>";
    mdl_y_doc *doc = calloc(1, sizeof *doc);
    if (doc) doc->file = strdup(name);
    if (!doc || !doc->file) {
        free(doc);
        if (e) snprintf(e->message, sizeof e->message, "%s: out of memory", name);
        return -1;
    }
    loader *L = calloc(1, sizeof *L);
    if (!L) {
        mdl_y_free(doc);
        if (e) snprintf(e->message, sizeof e->message, "%s: out of memory", name);
        return -1;
    }
    L->doc = doc;
    L->input = (const unsigned char *)text;
    L->len = text ? len : 0;
    L->e = e;
    int r;
    const char *nul = text ? memchr(text, 0, len) : NULL;
    if (!out) {
        r = lfail(L, 0, 0, "no place for the document");
    } else if (len > MDL_Y_MAX_BYTES) {
        r = lfail(L, 0, 0, "larger than %d bytes", MDL_Y_MAX_BYTES);
    } else if (nul) {
        int line, column;
        offset_position(L, (size_t)(nul - text), &line, &column);
        r = lfail(L, line, column, "NUL character in the text");
    } else {
        r = load_events(L);
    }
    for (int i = 0; i < L->depth; i++)
        free(L->stack[i].kids);
    free(L->anchors.e);
    free(L->keys.e);
    free(L);
    if (r < 0) {
        mdl_y_free(doc);
        return -1;
    }
    *out = doc;
    return 0;
}

int mdl_y_load_file(const char *path, mdl_y_doc **out, mdl_y_error *e)
{
    if (out) *out = NULL;
    if (e) memset(e, 0, sizeof *e);
    if (!path) path = "<no file>";
    FILE *f = fopen(path, "rb");
    if (!f) {
        int err = errno;
        char why[128] = "";
        if (strerror_r(err, why, sizeof why) != 0) snprintf(why, sizeof why, "errno %d", err);
        if (e) snprintf(e->message, sizeof e->message, "%s: cannot open: %s", path, why);
        return -1;
    }
    size_t cap = 4096, len = 0;
    char *buf = malloc(cap);
    int r = 0;
    while (buf) {
        if (len == cap) {
            if (cap > MDL_Y_MAX_BYTES) break;
            char *b = realloc(buf, 2 * cap);
            if (!b) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = b;
            cap *= 2;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    if (!buf) {
        if (e) snprintf(e->message, sizeof e->message, "%s: out of memory", path);
        r = -1;
    } else if (ferror(f)) {
        if (e) snprintf(e->message, sizeof e->message, "%s: read error", path);
        r = -1;
    } else if (len > MDL_Y_MAX_BYTES) {
        if (e)
            snprintf(e->message, sizeof e->message, "%s: larger than %d bytes", path,
                     MDL_Y_MAX_BYTES);
        r = -1;
    }
    fclose(f);
    if (r == 0) r = mdl_y_load_string(buf, len, path, out, e);
    free(buf);
    return r;
}

/* ---- lookups ---- */

const mdl_y_node *mdl_y_root(const mdl_y_doc *doc)
{
    return doc ? doc->root : NULL;
}
const char *mdl_y_file(const mdl_y_doc *doc)
{
    return doc ? doc->file : NULL;
}

static int find_key(const mdl_y_node *map, const char *key)
{
    if (!map || !key || map->kind != MDL_Y_MAPPING) return -1;
    size_t len = strlen(key);
    for (int i = 0; i < map->n; i++)
        if (map->pairs[i].key->len == len && !memcmp(map->pairs[i].key->text, key, len)) return i;
    return -1;
}

const mdl_y_node *mdl_y_get(const mdl_y_node *map, const char *key)
{
    int i = find_key(map, key);
    return i < 0 ? NULL : map->pairs[i].value;
}

const mdl_y_node *mdl_y_get_key(const mdl_y_node *map, const char *key)
{
    int i = find_key(map, key);
    return i < 0 ? NULL : map->pairs[i].key;
}

int mdl_y_count(const mdl_y_node *n)
{
    return n && n->kind != MDL_Y_SCALAR ? n->n : 0;
}

const mdl_y_node *mdl_y_item(const mdl_y_node *seq, int i)
{
    return seq && seq->kind == MDL_Y_SEQUENCE && i >= 0 && i < seq->n ? seq->items[i] : NULL;
}

const mdl_y_node *mdl_y_key(const mdl_y_node *map, int i)
{
    return map && map->kind == MDL_Y_MAPPING && i >= 0 && i < map->n ? map->pairs[i].key : NULL;
}

const mdl_y_node *mdl_y_value(const mdl_y_node *map, int i)
{
    return map && map->kind == MDL_Y_MAPPING && i >= 0 && i < map->n ? map->pairs[i].value : NULL;
}

int mdl_y_is_null(const mdl_y_node *n)
{
    if (!n || n->kind != MDL_Y_SCALAR || n->quoted) return 0;
    return !strcmp(n->text, "") || !strcmp(n->text, "~") || !strcmp(n->text, "null") ||
           !strcmp(n->text, "Null") || !strcmp(n->text, "NULL");
}

const char *mdl_y_kind_name(mdl_y_kind kind)
{
    return kind == MDL_Y_SCALAR ? "scalar" : kind == MDL_Y_SEQUENCE ? "sequence" : "mapping";
}

const char *mdl_y_where(const mdl_y_node *node, char *buf, size_t size)
{
    if (!buf || !size) return buf;
    if (!node)
        snprintf(buf, size, "?");
    else
        snprintf(buf, size, "%s:%d:%d", node->file, node->line, node->column);
    return buf;
}
