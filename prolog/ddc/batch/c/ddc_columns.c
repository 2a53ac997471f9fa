/*  ddc_columns.c -- the batched filter's columns as arrays, and their loops.

    Part of the batched particle filter (prolog/ddc/batch/ddc_batch.pl): the values of
    a random variable at a time, one per particle, held in C memory as a
    blob (an atom whose data is a column struct), and the loops over a
    batch of particles that the engine runs most (what is drawn and what
    not, a column's status, draws and densities of a gaussian, resampling).
    prolog/ddc/batch/ddc_batch_col.pl loads it (use_foreign_library/1) and falls back
    on plain Prolog terms c(V1, ..., VN) when it is not built; the set-up
    builds it (scripts/setup.sh, with the swipl-ld of the SWI-Prolog it
    installs).

    A cell holds one particle's value: '$u' (not drawn yet), '$undef' (no
    clause applies), a number tuple (K floats, K the column's arity, fixed
    by the first such value: a float is a 1-tuple, (X, Y, Z) of floats a
    3-tuple), an atom, or any other term (recorded: PL_record/3).  A
    column is updated in place (as nb_setarg/3 updates a term: not undone
    on backtracking) and freed when the atom garbage collector finds it
    unreferenced.

    A batch of particles is a blob too (a C array of indices), or a Prolog
    list (BATCHES below); a column that every particle agrees on stores one
    cell (a uniform column, CI/2); the loops over a batch compile the goal's
    arithmetic to a small register machine (LOOPS); the rows of a variable
    are read into a caller's memory (col_floats_into/4).

    The random draws come from a xoshiro256+ generator seeded, at each
    call, with a seed that the caller draws from the filter's own Prolog
    random stream: the particles still depend on the filter's seed alone.
    Its normals are a ziggurat's.
*/

#include <SWI-Stream.h>
#include <SWI-Prolog.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <math.h>

#define DDC_COLUMNS_VERSION 5

#define T_U      0                      /* '$u': not drawn yet */
#define T_UNDEF  1                      /* '$undef': no clause applies */
#define T_NUM    2                      /* a tuple of k floats */
#define T_ATOM   3                      /* an atom (registered) */
#define T_TERM   4                      /* any other term (a record) */
#define T_LIST   5                      /* a non-empty list of ground terms (an alist) */
#define N_TAGS   6

/* A list of ground terms, as a cell holds it: appending is cheap
   (findall's lists of instances), and a partition or a uniform draw reads it
   without making the list.  An item is an atom (registered) or a record
   (rec set). */
typedef struct item { uintptr_t v; int rec; } item;
typedef struct alist { size_t n, cap; item a[]; } alist;

typedef struct column
{ size_t    n;                          /* particles */
  int       k;                          /* arity of the T_NUM cells (0: none yet) */
  uint8_t  *tag;                        /* n tags */
  double   *f;                          /* n*k floats (k > 0) */
  uintptr_t *x;                         /* n atoms or records (allocated lazily) */
  size_t    cnt[N_TAGS];                /* the number of cells of each tag */
  uint32_t *cls;                        /* class of each cell: equal values, equal
					   classes (valid while cls_valid) */
  int       cls_valid;
  int       uni;                        /* every cell holds cell 0's value, the only
					   one stored (the arrays have one cell) */
} column;

/* A uniform column (uni) holds one value for all its cells: made by
   col_new/3, kept by the writes that give every cell the same value
   (col_set_each/3, col_append_each/3 and col_sets_each/3 over every
   particle) and read as it is (CI(c, i): the stored cell of particle i);
   any other write expands it first (expand/1).  A column of 10,000
   particles that every particle agrees on (a perceived object's position,
   a flag, a list of instances) costs one cell, not 10,000. */
#define CI(c, i) ((c)->uni ? (size_t)0 : (size_t)(i))

/* SET_TAG(c, i, t): cell i's tag is t (the counts kept) */
#define SET_TAG(c, i, t) \
	do { uint8_t t_ = (t); column *c_ = (c); size_t i_ = (i); \
	     c_->cnt[c_->tag[i_]]--; c_->tag[i_] = t_; c_->cnt[t_]++; \
	     c_->cls_valid = 0; } while(0)

/* The bytes of column memory allocated since the last col_gc_due/1 that
   succeeded: columns are freed by the atom garbage collector, which
   counts atoms, not bytes; the engine asks for a collection when this
   grows (a column of 10,000 particles holds hundreds of kilobytes). */
static size_t col_bytes = 0;

static void
count_bytes(size_t n)
{ __atomic_add_fetch(&col_bytes, n, __ATOMIC_RELAXED);
}

static atom_t ATOM_u, ATOM_undef, ATOM_open, ATOM_defined, ATOM_mixed, ATOM_done, ATOM_none;
static functor_t FUNCTOR_comma2, FUNCTOR_same1, FUNCTOR_minus2;

		 /*******************************
		 *             BLOB             *
		 *******************************/

static void
free_alist(alist *l)
{ for(size_t q=0; q<l->n; q++)
  { if ( l->a[q].rec ) PL_erase((record_t)l->a[q].v);
    else PL_unregister_atom((atom_t)l->a[q].v);
  }
  free(l);
}

/* put_item(t, it): t is the item's term */
static int
put_item(term_t t, const item *it)
{ return it->rec ? PL_recorded((record_t)it->v, t) : PL_put_atom(t, (atom_t)it->v);
}

/* make_item(t, &it): t (ground) as an item */
static int
make_item(term_t t, item *it)
{ atom_t a;
  if ( PL_get_atom(t, &a) )
  { PL_register_atom(a);
    it->v = (uintptr_t)a; it->rec = FALSE;
    return TRUE;
  }
  { record_t r = PL_record(t);
    if ( !r ) return FALSE;
    it->v = (uintptr_t)r; it->rec = TRUE;
    return TRUE;
  }
}

static void
free_item(item *it)
{ if ( it->rec ) PL_erase((record_t)it->v);
  else PL_unregister_atom((atom_t)it->v);
}

/* copy_item(&to, from): a copy of the item (registered or duplicated) */
static void
copy_item(item *to, const item *from)
{ if ( from->rec ) to->v = (uintptr_t)PL_duplicate_record((record_t)from->v);
  else { PL_register_atom((atom_t)from->v); to->v = from->v; }
  to->rec = from->rec;
}

static alist *
new_alist(size_t cap)
{ alist *l = malloc(sizeof(alist) + (cap ? cap : 1)*sizeof(item));
  if ( l ) { l->n = 0; l->cap = cap ? cap : 1; }
  return l;
}

/* alist_push(&l, it): a copy of the item appended */
static int
alist_push(alist **lp, const item *it)
{ alist *l = *lp;
  if ( l->n == l->cap )
  { alist *l2 = realloc(l, sizeof(alist) + 2*l->cap*sizeof(item));
    if ( !l2 ) return FALSE;
    l2->cap *= 2;
    *lp = l = l2;
  }
  copy_item(&l->a[l->n++], it);
  return TRUE;
}

static void
free_cells(column *c)
{ if ( c->x )
  { size_t n = c->uni ? (c->n ? 1 : 0) : c->n;
    for(size_t i=0; i<n; i++)
    { if ( c->tag[i] == T_ATOM )
	PL_unregister_atom((atom_t)c->x[i]);
      else if ( c->tag[i] == T_TERM )
	PL_erase((record_t)c->x[i]);
      else if ( c->tag[i] == T_LIST )
	free_alist((alist*)c->x[i]);
    }
  }
  free(c->tag); free(c->f); free(c->x); free(c->cls);
  free(c);
}

static int
release_column(atom_t a)
{ column *c = PL_blob_data(a, NULL, NULL);
  if ( c ) free_cells(c);
  return TRUE;
}

static int
write_column(IOSTREAM *s, atom_t a, int flags)
{ column *c = PL_blob_data(a, NULL, NULL);
  (void)flags;
  Sfprintf(s, "<ddc_column>(%zu)", c ? c->n : (size_t)0);
  return TRUE;
}

static PL_blob_t column_blob =
{ .magic   = PL_BLOB_MAGIC,
  .flags   = PL_BLOB_NOCOPY|PL_BLOB_UNIQUE,
  .name    = "ddc_column",
  .release = release_column,
  .write   = write_column
};

/* get_column_raw(t, &c): t is a column (uniform or not: its cells read
   through CI/2) */
static int
get_column_raw(term_t t, column **cp)
{ void *data; PL_blob_t *type;
  *cp = NULL;
  if ( PL_get_blob(t, &data, NULL, &type) && type == &column_blob )
  { *cp = (column*)data;
    return TRUE;
  }
  return PL_type_error("ddc_column", t);
}

static int expand(column *c);

/* get_column(t, &c): t is a column, expanded if it was uniform (for the
   code that reads and writes its cells by index) */
static int
get_column(term_t t, column **cp)
{ return get_column_raw(t, cp) && expand(*cp);
}

static column *
new_column(size_t n)
{ column *c = calloc(1, sizeof(*c));
  if ( !c ) return NULL;
  c->n = n;
  c->tag = calloc(n ? n : 1, 1);
  if ( !c->tag ) { free(c); return NULL; }
  count_bytes(sizeof(*c) + n);
  c->cnt[T_U] = n;
  return c;
}

/* new_uniform(n): a uniform column of n particles, each '$u' */
static column *
new_uniform(size_t n)
{ column *c;
  if ( n == 0 ) return new_column(0);
  if ( !(c = calloc(1, sizeof(*c))) ) return NULL;
  c->n = n;
  if ( !(c->tag = calloc(1, 1)) ) { free(c); return NULL; }
  c->uni = 1;
  c->cnt[T_U] = n;
  count_bytes(sizeof(*c));
  return c;
}

static int
unify_column(term_t t, column *c)
{ if ( !PL_unify_blob(t, c, sizeof(*c), &column_blob) )
  { /* (the blob is not made: nothing refers to c) */
    return FALSE;
  }
  return TRUE;
}

static int
ensure_x(column *c)
{ if ( !c->x )
  { size_t n = c->uni ? 1 : c->n;
    c->x = calloc(n ? n : 1, sizeof(uintptr_t));
    if ( !c->x ) return PL_resource_error("memory");
    count_bytes(n*sizeof(uintptr_t));
  }
  return TRUE;
}

static int
set_k(column *c, int k)
{ size_t n = c->uni ? 1 : c->n;
  c->f = calloc((n ? n : 1)*(size_t)k, sizeof(double));
  if ( !c->f ) return PL_resource_error("memory");
  count_bytes(n*(size_t)k*sizeof(double));
  c->k = k;
  return TRUE;
}

		 /*******************************
		 *            CELLS             *
		 *******************************/

static void
clear_cell(column *c, size_t i)
{ if ( c->tag[i] == T_ATOM )
    PL_unregister_atom((atom_t)c->x[i]);
  else if ( c->tag[i] == T_TERM )
    PL_erase((record_t)c->x[i]);
  else if ( c->tag[i] == T_LIST )
    free_alist((alist*)c->x[i]);
  SET_TAG(c, i, T_U);
}

/* float_tuple(t, fs, max): the number of elements of t as a tuple of
   floats (a float: 1; (A, B, ...) of floats: their number), 0 if it is
   not one; fs gets them (at most max). */
static int
float_tuple(term_t t, double *fs, int max)
{ term_t h = PL_new_term_ref();
  term_t r = PL_copy_term_ref(t);
  int m = 0;

  for(;;)
  { if ( PL_is_functor(r, FUNCTOR_comma2) )
    { _PL_get_arg(1, r, h);
      if ( !PL_is_float(h) || m >= max || !PL_get_float(h, &fs[m++]) ) return 0;
      _PL_get_arg(2, r, r);
    } else if ( PL_is_float(r) )
    { if ( m >= max || !PL_get_float(r, &fs[m++]) ) return 0;
      return m;
    } else
      return 0;
  }
}

#define MAX_K 16

/* set_cell_raw(c, i, v): cell i (of the cells stored) gets the value v
   (the previous one freed) */
static int
set_cell_raw(column *c, size_t i, term_t v)
{ atom_t a;
  double fs[MAX_K];
  int m;

  if ( PL_get_atom(v, &a) )
  { clear_cell(c, i);
    if ( a == ATOM_u ) { SET_TAG(c, i, T_U); return TRUE; }
    if ( a == ATOM_undef ) { SET_TAG(c, i, T_UNDEF); return TRUE; }
    if ( !ensure_x(c) ) return FALSE;
    PL_register_atom(a);
    c->x[i] = (uintptr_t)a;
    SET_TAG(c, i, T_ATOM);
    return TRUE;
  }
  if ( (m=float_tuple(v, fs, MAX_K)) > 0 )
  { if ( c->k == 0 && !set_k(c, m) ) return FALSE;
    if ( c->k == m )
    { clear_cell(c, i);
      memcpy(&c->f[i*(size_t)m], fs, sizeof(double)*(size_t)m);
      SET_TAG(c, i, T_NUM);
      return TRUE;
    }
  }
  { size_t len;
    if ( PL_is_pair(v) && PL_skip_list(v, 0, &len) == PL_LIST )
    { term_t l = PL_copy_term_ref(v), h = PL_new_term_ref();
      alist *al;
      if ( PL_is_ground(v) )		/* (items recorded apart: no variables to share) */
      { if ( !ensure_x(c) || !(al = new_alist(len)) ) return FALSE;
	while( PL_get_list(l, h, l) )
	{ if ( !make_item(h, &al->a[al->n]) ) { free_alist(al); return FALSE; }
	  al->n++;
	}
	clear_cell(c, i);
	c->x[i] = (uintptr_t)al;
	SET_TAG(c, i, T_LIST);
	return TRUE;
      }
    }
  }
  { record_t r;
    if ( !ensure_x(c) ) return FALSE;
    if ( !(r = PL_record(v)) ) return FALSE;
    clear_cell(c, i);
    c->x[i] = (uintptr_t)r;
    SET_TAG(c, i, T_TERM);
    return TRUE;
  }
}

/* set_cell(c, i, v): particle i's cell gets the value v (a uniform column
   expanded first) */
static int
set_cell(column *c, size_t i, term_t v)
{ if ( c->uni && !expand(c) ) return FALSE;
  return set_cell_raw(c, i, v);
}

/* set_uniform(c, v): every cell of the uniform column c gets v */
static int
set_uniform(column *c, term_t v)
{ int rc = set_cell_raw(c, 0, v);
  memset(c->cnt, 0, sizeof(c->cnt));
  c->cnt[c->tag[0]] = c->n;
  c->cls_valid = 0;
  return rc;
}

/* expand(c): a uniform column c becomes a column of n cells, each a copy of
   its value */
static int
expand(column *c)
{ size_t n = c->n;
  uint8_t t;
  uint8_t *tag;
  double *f = NULL;
  uintptr_t *x = NULL;
  if ( !c->uni ) return TRUE;
  t = c->tag[0];
  if ( !(tag = malloc(n ? n : 1)) ) return PL_resource_error("memory");
  memset(tag, t, n);
  if ( c->k )
  { if ( !(f = malloc(n*(size_t)c->k*sizeof(double))) ) { free(tag); return PL_resource_error("memory"); }
    if ( t == T_NUM )
      for(size_t i=0; i<n; i++) memcpy(&f[i*(size_t)c->k], c->f, sizeof(double)*(size_t)c->k);
    else
      memset(f, 0, n*(size_t)c->k*sizeof(double));
  }
  if ( c->x )
  { if ( !(x = calloc(n, sizeof(uintptr_t))) )
    { free(f); free(tag); return PL_resource_error("memory"); }
    x[0] = c->x[0];
    for(size_t i=1; i<n; i++)
    { switch(t)
      { case T_ATOM:
	  PL_register_atom((atom_t)c->x[0]);
	  x[i] = c->x[0];
	  break;
	case T_TERM:
	  x[i] = (uintptr_t)PL_duplicate_record((record_t)c->x[0]);
	  break;
	case T_LIST:
	{ alist *from = (alist*)c->x[0], *l = new_alist(from->n);
	  if ( !l ) return PL_resource_error("memory");	/* (leaks what was copied) */
	  for(size_t q=0; q<from->n; q++) copy_item(&l->a[q], &from->a[q]);
	  l->n = from->n;
	  x[i] = (uintptr_t)l;
	  break;
	}
      }
    }
  }
  free(c->tag); free(c->f); free(c->x);
  c->tag = tag; c->f = f; c->x = x;
  c->uni = 0;
  c->cls_valid = 0;
  count_bytes(n*(1 + (size_t)c->k*sizeof(double) + (x ? sizeof(uintptr_t) : 0)));
  return TRUE;
}

/* put_floats(t, fs, k): t is the k-tuple of the floats fs */
static int
put_floats(term_t t, const double *fs, int k)
{ if ( k == 1 )
    return PL_put_float(t, fs[0]);
  { term_t h = PL_new_term_ref();
    if ( !PL_put_float(t, fs[k-1]) ) return FALSE;
    for(int j=k-2; j>=0; j--)
    { if ( !PL_put_float(h, fs[j]) ||
	   !PL_cons_functor(t, FUNCTOR_comma2, h, t) )
	return FALSE;
    }
    return TRUE;
  }
}

/* put_cell(t, c, i): t is particle i's value in c */
static int
put_cell(term_t t, column *c, size_t i)
{ i = CI(c, i);
  switch(c->tag[i])
  { case T_U:     return PL_put_atom(t, ATOM_u);
    case T_UNDEF: return PL_put_atom(t, ATOM_undef);
    case T_NUM:   return put_floats(t, &c->f[i*(size_t)c->k], c->k);
    case T_ATOM:  return PL_put_atom(t, (atom_t)c->x[i]);
    case T_TERM:  return PL_recorded((record_t)c->x[i], t);
    case T_LIST:
    { alist *l = (alist*)c->x[i];
      term_t h = PL_new_term_ref();
      PL_put_nil(t);
      for(size_t q=l->n; q-- > 0; )
      { if ( !put_item(h, &l->a[q]) || !PL_cons_list(t, h, t) ) return FALSE;
      }
      return TRUE;
    }
  }
  return FALSE;
}

/* copy_cell(d, j, s, i): d's cell j is s's cell i */
static int
copy_cell(column *d, size_t j, column *s, size_t i)
{ i = CI(s, i);
  if ( d->uni && !expand(d) ) return FALSE;
  switch(s->tag[i])
  { case T_U:
    case T_UNDEF:
      clear_cell(d, j);
      SET_TAG(d, j, s->tag[i]);
      return TRUE;
    case T_NUM:
      if ( d->k == 0 && !set_k(d, s->k) ) return FALSE;
      if ( d->k == s->k )
      { clear_cell(d, j);
	memcpy(&d->f[j*(size_t)d->k], &s->f[i*(size_t)s->k], sizeof(double)*(size_t)d->k);
	SET_TAG(d, j, T_NUM);
	return TRUE;
      }
      { term_t t = PL_new_term_ref();
	int rc = put_cell(t, s, i) && set_cell(d, j, t);
	PL_reset_term_refs(t);
	return rc;
      }
    case T_ATOM:
      if ( !ensure_x(d) ) return FALSE;
      clear_cell(d, j);
      PL_register_atom((atom_t)s->x[i]);
      d->x[j] = s->x[i];
      SET_TAG(d, j, T_ATOM);
      return TRUE;
    case T_TERM:
      if ( !ensure_x(d) ) return FALSE;
      clear_cell(d, j);
      d->x[j] = (uintptr_t)PL_duplicate_record((record_t)s->x[i]);
      SET_TAG(d, j, T_TERM);
      return TRUE;
    case T_LIST:
    { alist *from = (alist*)s->x[i], *l;
      if ( !ensure_x(d) || !(l = new_alist(from->n)) ) return FALSE;
      for(size_t q=0; q<from->n; q++) copy_item(&l->a[q], &from->a[q]);
      l->n = from->n;
      clear_cell(d, j);
      d->x[j] = (uintptr_t)l;
      SET_TAG(d, j, T_LIST);
      return TRUE;
    }
  }
  return FALSE;
}

/* same_cell(a, i, b, j): the two values are == */
static int
same_cell(column *a, size_t i, column *b, size_t j)
{ i = CI(a, i); j = CI(b, j);
  if ( a->tag[i] != b->tag[j] )
  { if ( a->tag[i] == T_TERM || b->tag[j] == T_TERM )
      goto general;
    return FALSE;
  }
  switch(a->tag[i])
  { case T_U:
    case T_UNDEF:
      return TRUE;
    case T_NUM:
      if ( a->k != b->k ) goto general;
      return memcmp(&a->f[i*(size_t)a->k], &b->f[j*(size_t)b->k],
		    sizeof(double)*(size_t)a->k) == 0;
    case T_ATOM:
      return a->x[i] == b->x[j];
    case T_LIST:
    { alist *la = (alist*)a->x[i], *lb = (alist*)b->x[j];
      if ( la->n != lb->n ) return FALSE;
      for(size_t q=0; q<la->n; q++)
      { if ( la->a[q].rec || lb->a[q].rec ) goto general;
	if ( la->a[q].v != lb->a[q].v ) return FALSE;
      }
      return TRUE;
    }
    case T_TERM:
      goto general;
  }
general:
  { fid_t fid = PL_open_foreign_frame();
    term_t t1 = PL_new_term_ref(), t2 = PL_new_term_ref();
    int rc = put_cell(t1, a, i) && put_cell(t2, b, j) && PL_compare(t1, t2) == 0;
    PL_discard_foreign_frame(fid);
    return rc;
  }
}

/* index(t, c, &i): t is a particle index of c, i its 0-based index */
static int
get_index(term_t t, column *c, size_t *ip)
{ int64_t i;
  if ( !PL_get_int64_ex(t, &i) ) return FALSE;
  if ( i < 1 || (uint64_t)i > c->n ) return FALSE;
  *ip = (size_t)(i-1);
  return TRUE;
}

		 /*******************************
		 *           BATCHES            *
		 *******************************/

/* A batch is a set of particle indices: a Prolog list of integers 1..N in
   ascending order, or a blob of the same set held as a C array (0-based,
   ascending), which is what the engine passes from call to call (a list
   of N integers is walked and built again by every call; a blob is
   passed as it is).  The empty batch is [] in both.  Every predicate
   here takes either; one that makes a batch makes a blob if its (first)
   batch argument is one, else a list, so that a caller that passes lists
   gets lists back. */

/* Blobs that are one malloc'd struct whose first member is its count
   (pset, frows, gplan): freed whole, written as <name>(count). */
static int
release_counted(atom_t a)
{ free(PL_blob_data(a, NULL, NULL));
  return TRUE;
}

static int
write_counted(IOSTREAM *s, atom_t a, int flags)
{ PL_blob_t *type;
  const size_t *n = PL_blob_data(a, NULL, &type);
  (void)flags;
  Sfprintf(s, "<%s>(%zu)", type->name, n ? *n : (size_t)0);
  return TRUE;
}

typedef struct pset { size_t n; uint32_t v[]; } pset;

static PL_blob_t pset_blob =
{ .magic   = PL_BLOB_MAGIC,
  .flags   = PL_BLOB_NOCOPY|PL_BLOB_UNIQUE,
  .name    = "ddc_batch",
  .release = release_counted,
  .write   = write_counted
};

/* A view of a batch: its n indices (0-based, ascending) v, owned (to be
   freed) when read from a list */
typedef struct pview { const uint32_t *v; size_t n; uint32_t *own; int blob; } pview;

static void
free_view(pview *p)
{ free(p->own);
  p->own = NULL;
}

static int
is_pset(term_t t, pset **pp)
{ void *data; PL_blob_t *type;
  if ( PL_get_blob(t, &data, NULL, &type) && type == &pset_blob )
  { *pp = data;
    return TRUE;
  }
  return FALSE;
}

/* get_view(t, limit, &p): t is a batch whose indices are at most limit
   (0: any); FALSE, with no exception but a resource error, if it is not
   one */
static int
get_view(term_t t, size_t limit, pview *p)
{ pset *s;
  p->own = NULL;
  if ( is_pset(t, &s) )
  { if ( limit && s->n && s->v[s->n-1] >= limit ) return FALSE;
    p->v = s->v; p->n = s->n; p->blob = TRUE;
    return TRUE;
  }
  { size_t n;
    term_t l = PL_copy_term_ref(t), h = PL_new_term_ref();
    if ( PL_skip_list(t, 0, &n) != PL_LIST ) return FALSE;
    if ( !(p->own = malloc((n ? n : 1)*sizeof(uint32_t))) ) return PL_resource_error("memory");
    for(size_t j=0; PL_get_list(l, h, l); j++)
    { int64_t i;
      if ( !PL_get_int64(h, &i) || i < 1 || i > (int64_t)UINT32_MAX ||
	   (limit && (uint64_t)i > limit) )
      { free_view(p); return FALSE; }
      p->own[j] = (uint32_t)(i-1);
    }
    p->v = p->own; p->n = n; p->blob = FALSE;
    return TRUE;
  }
}

/* unify_batch(t, v, n, blob): t is the batch of the n indices v (0-based,
   ascending): [] if n = 0, else a blob (blob) or a list */
static int
unify_batch(term_t t, const uint32_t *v, size_t n, int blob)
{ if ( n == 0 ) return PL_unify_nil(t);
  if ( blob )
  { pset *s = malloc(sizeof(pset) + n*sizeof(uint32_t));
    if ( !s ) return PL_resource_error("memory");
    s->n = n;
    memcpy(s->v, v, n*sizeof(uint32_t));
    count_bytes(sizeof(pset) + n*sizeof(uint32_t));
    if ( !PL_unify_blob(t, s, sizeof(*s), &pset_blob) ) { free(s); return FALSE; }
    return TRUE;
  }
  { term_t l = PL_new_term_ref(), h = PL_new_term_ref();
    PL_put_nil(l);
    for(size_t j=n; j-- > 0; )
    { if ( !PL_put_int64(h, (int64_t)v[j]+1) || !PL_cons_list(l, h, l) ) return FALSE;
    }
    return PL_unify(t, l);
  }
}

/* unify_selected(t, in, p, keep, m): t is the batch of the elements of p
   whose keep is set (m of them): in itself if every one is */
static int
unify_selected(term_t t, term_t in, const pview *p, const char *keep, size_t m)
{ if ( m == p->n ) return PL_unify(t, in);
  if ( m == 0 ) return PL_unify_nil(t);
  { uint32_t *v = malloc(m*sizeof(uint32_t));
    size_t q = 0;
    int rc;
    if ( !v ) return PL_resource_error("memory");
    for(size_t j=0; j<p->n; j++) if ( keep[j] ) v[q++] = p->v[j];
    rc = unify_batch(t, v, m, p->blob);
    free(v);
    return rc;
  }
}

/* ps_all(+N, -Ps): the batch of every particle 1..N, a blob */
static foreign_t
ps_all(term_t tn, term_t out)
{ int64_t n;
  if ( !PL_get_int64_ex(tn, &n) ) return FALSE;
  if ( n < 0 || n > (int64_t)UINT32_MAX ) return PL_domain_error("particle_count", tn);
  if ( n == 0 ) return PL_unify_nil(out);
  { pset *s = malloc(sizeof(pset) + (size_t)n*sizeof(uint32_t));
    if ( !s ) return PL_resource_error("memory");
    s->n = (size_t)n;
    for(size_t j=0; j<s->n; j++) s->v[j] = (uint32_t)j;
    count_bytes(sizeof(pset) + s->n*sizeof(uint32_t));
    if ( !PL_unify_blob(out, s, sizeof(*s), &pset_blob) ) { free(s); return FALSE; }
    return TRUE;
  }
}

/* ps_list(+Ps, -List): the batch's indices as a list (a list as it is) */
static foreign_t
ps_list(term_t ps, term_t out)
{ pset *s;
  if ( is_pset(ps, &s) ) return unify_batch(out, s->v, s->n, FALSE);
  return PL_unify(out, ps);
}

/* ps_blob(+Ps, -Blob): the batch as a blob ([] if empty) */
static foreign_t
ps_blob(term_t ps, term_t out)
{ pview p;
  int rc;
  if ( !get_view(ps, 0, &p) ) return PL_exception(0) ? FALSE : PL_type_error("ddc_batch", ps);
  if ( p.blob ) return PL_unify(out, ps);
  rc = unify_batch(out, p.v, p.n, TRUE);
  free_view(&p);
  return rc;
}

/* ps_size(+Ps, -K) */
static foreign_t
ps_size(term_t ps, term_t tk)
{ pset *s;
  size_t n;
  if ( is_pset(ps, &s) ) return PL_unify_int64(tk, (int64_t)s->n);
  if ( PL_skip_list(ps, 0, &n) != PL_LIST ) return PL_type_error("list", ps);
  return PL_unify_int64(tk, (int64_t)n);
}

/* ps_first(+Ps, -I): the batch's first (least) index; fails if empty */
static foreign_t
ps_first(term_t ps, term_t ti)
{ pset *s;
  if ( is_pset(ps, &s) ) return s->n > 0 && PL_unify_int64(ti, (int64_t)s->v[0]+1);
  { term_t h = PL_new_term_ref(), t = PL_new_term_ref();
    return PL_get_list(ps, h, t) && PL_unify(ti, h);
  }
}

		 /*******************************
		 *          PREDICATES          *
		 *******************************/

/* col_new(+N, +V, -C) */
static foreign_t
col_new(term_t tn, term_t v, term_t tc)
{ int64_t n;
  column *c;
  if ( !PL_get_int64_ex(tn, &n) ) return FALSE;
  if ( n < 0 ) return PL_domain_error("not_less_than_zero", tn);
  if ( !(c = new_uniform((size_t)n)) ) return PL_resource_error("memory");
  { atom_t a;
    if ( PL_get_atom(v, &a) && a == ATOM_u )
      ;					/* (all T_U) */
    else if ( c->uni )
    { if ( !set_uniform(c, v) ) { free_cells(c); return FALSE; }
    } else
    { for(size_t i=0; i<c->n; i++)
      { if ( !set_cell(c, i, v) ) { free_cells(c); return FALSE; }
      }
    }
  }
  if ( !unify_column(tc, c) ) { free_cells(c); return FALSE; }
  return TRUE;
}

/* col_arg(+I, +C, ?V) */
static foreign_t
col_arg(term_t ti, term_t tc, term_t v)
{ column *c = NULL; size_t i;
  if ( !get_column_raw(tc, &c) || !get_index(ti, c, &i) ) return FALSE;
  { term_t t = PL_new_term_ref();
    return put_cell(t, c, i) && PL_unify(t, v);
  }
}

/* col_setarg(+I, +C, +V) */
static foreign_t
col_setarg(term_t ti, term_t tc, term_t v)
{ column *c = NULL; size_t i;
  if ( !get_column(tc, &c) || !get_index(ti, c, &i) ) return FALSE;
  return set_cell(c, i, v);
}

/* col_is_u(+I, +C): particle I's value is not drawn yet */
static foreign_t
col_is_u(term_t ti, term_t tc)
{ column *c = NULL; size_t i;
  if ( !get_column_raw(tc, &c) || !get_index(ti, c, &i) ) return FALSE;
  return c->tag[CI(c, i)] == T_U;
}

/* col_size(+C, -N) */
static foreign_t
col_size(term_t tc, term_t tn)
{ column *c = NULL;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  return PL_unify_int64(tn, (int64_t)c->n);
}

/* col_is(@C) */
static foreign_t
col_is(term_t tc)
{ void *data; PL_blob_t *type;
  return PL_get_blob(tc, &data, NULL, &type) && type == &column_blob;
}

/* col_list(+C, -Vs) */
static foreign_t
col_list(term_t tc, term_t vs)
{ column *c = NULL;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  { term_t l = PL_new_term_ref(), h = PL_new_term_ref();
    PL_put_nil(l);
    for(size_t i=c->n; i-- > 0; )
    { if ( !put_cell(h, c, i) || !PL_cons_list(l, h, l) ) return FALSE;
    }
    return PL_unify(l, vs);
  }
}

/* col_from_list(+Vs, -C) */
static foreign_t
col_from_list(term_t vs, term_t tc)
{ size_t n;
  column *c;
  if ( !PL_skip_list(vs, 0, &n) ) return PL_type_error("list", vs);
  if ( !(c = new_column(n)) ) return PL_resource_error("memory");
  { term_t l = PL_copy_term_ref(vs), h = PL_new_term_ref();
    for(size_t i=0; PL_get_list(l, h, l); i++)
    { if ( !set_cell(c, i, h) ) { free_cells(c); return FALSE; }
    }
  }
  if ( !unify_column(tc, c) ) { free_cells(c); return FALSE; }
  return TRUE;
}

/* Walks a batch with the particles whose cell satisfies a test
   collected in a batch. */
typedef int (*cell_test)(column *c, size_t i);

static int test_u(column *c, size_t i) { return c->tag[CI(c, i)] == T_U; }
static int test_defined(column *c, size_t i) { return c->tag[CI(c, i)] >= T_NUM; }

static foreign_t
select_cells(term_t ps, term_t tc, term_t out, cell_test test)
{ column *c = NULL;
  pview p;
  char *keep;
  size_t m = 0;
  int rc;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( !get_view(ps, c->n, &p) )
    return PL_exception(0) ? FALSE : PL_domain_error("particle_batch", ps);
  if ( !(keep = malloc(p.n ? p.n : 1)) ) { free_view(&p); return PL_resource_error("memory"); }
  for(size_t j=0; j<p.n; j++)
  { keep[j] = (char)(*test)(c, p.v[j]);
    m += (size_t)keep[j];
  }
  rc = unify_selected(out, ps, &p, keep, m);
  free(keep); free_view(&p);
  return rc;
}

/* col_uncomputed(+Ps, +C, -Missing) */
static foreign_t
col_uncomputed(term_t ps, term_t tc, term_t out)
{ column *c = NULL;
  if ( PL_get_blob(tc, (void**)&c, NULL, NULL) && col_is(tc) )
  { if ( c->cnt[T_U] == 0 ) return PL_unify_nil(out);
    if ( c->cnt[T_U] == c->n ) return PL_unify(out, ps);   /* (every particle of Ps) */
  }
  return select_cells(ps, tc, out, test_u);
}

/* col_defined_at(+Ps, +C, -Defined) */
static foreign_t
col_defined_at(term_t ps, term_t tc, term_t out)
{ column *c = NULL;
  if ( PL_get_blob(tc, (void**)&c, NULL, NULL) && col_is(tc) &&
       c->cnt[T_U] + c->cnt[T_UNDEF] == 0 )
    return PL_unify(out, ps);
  return select_cells(ps, tc, out, test_defined);
}

/* col_set_each(+Ps, +C, +V): each particle of Ps not drawn yet gets V */
static foreign_t
col_set_each(term_t ps, term_t tc, term_t v)
{ column *c = NULL;
  pview p;
  size_t first = (size_t)-1;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( c->cnt[T_U] == 0 ) return TRUE;
  if ( !get_view(ps, c->n, &p) ) return FALSE;
  if ( c->uni && p.n == c->n )		/* (every particle: the column stays uniform) */
  { free_view(&p);
    return set_uniform(c, v);
  }
  if ( !expand(c) ) { free_view(&p); return FALSE; }
  for(size_t j=0; j<p.n; j++)
  { size_t i = p.v[j];
    if ( c->tag[i] == T_U )
    { if ( first == (size_t)-1 )
      { if ( !set_cell(c, i, v) ) { free_view(&p); return FALSE; }
	first = i;
      } else if ( !copy_cell(c, i, c, first) )
      { free_view(&p); return FALSE; }
    }
  }
  free_view(&p);
  return TRUE;
}

/* col_rows(+C, ?W, -Floats, ?Tail): each particle's value in C as a row of
   W floats, particle by particle (a row of NaNs where it has none), then
   Tail; fails unless every value is a tuple of W floats ('$u', '$undef'
   aside) and one at least is (W unbound: the column's arity) */
static foreign_t
col_rows(term_t tc, term_t tw, term_t out, term_t tail)
{ column *c;
  int w;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( c->cnt[T_NUM] == 0 || c->cnt[T_NUM] + c->cnt[T_U] + c->cnt[T_UNDEF] != c->n )
    return FALSE;
  if ( PL_is_variable(tw) )
  { if ( !PL_unify_integer(tw, c->k) ) return FALSE;
    w = c->k;
  } else if ( !PL_get_integer(tw, &w) || w != c->k )
    return FALSE;
  { term_t l = PL_copy_term_ref(tail), h = PL_new_term_ref();
    for(size_t i=c->n; i-- > 0; )
    { for(int q=w; q-- > 0; )
      { size_t ii = CI(c, i);
	double x = c->tag[ii] == T_NUM ? c->f[ii*(size_t)w+(size_t)q] : NAN;
	if ( !PL_put_float(h, x) || !PL_cons_list(l, h, l) ) return FALSE;
      }
    }
    return PL_unify(out, l);
  }
}

/* col_row_width(+C, -W): every value in C is a tuple of W floats, '$u' and
   '$undef' aside (W 0 if there is none); fails if another value is there */
static foreign_t
col_row_width(term_t tc, term_t tw)
{ column *c;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( c->cnt[T_NUM] + c->cnt[T_U] + c->cnt[T_UNDEF] != c->n ) return FALSE;
  return PL_unify_integer(tw, c->cnt[T_NUM] > 0 ? c->k : 0);
}

/* Rows of floats held in C (a blob), made in the filter's engine and read
   by another thread: an atom is not copied out of an engine, a list of
   30,000 floats is; the Python bridge then has them copied into a numpy
   array's memory (col_floats_into/4) instead of converting each float. */

typedef struct frows { size_t n; double v[]; } frows;

static PL_blob_t frows_blob =
{ .magic   = PL_BLOB_MAGIC,
  .flags   = PL_BLOB_NOCOPY|PL_BLOB_UNIQUE,
  .name    = "ddc_floats",
  .release = release_counted,
  .write   = write_counted
};

/* col_pack_rows(+Columns, +W, -Rows): the rows of col_rows/4 of each column
   in turn (of W floats each, NaNs where a particle has no value), as a
   blob of doubles; fails where col_rows/4 would (a value that is not a
   tuple of W floats) */
static foreign_t
col_pack_rows(term_t tcols, term_t tw, term_t out)
{ size_t n = 0, j = 0;
  int w;
  frows *r;
  term_t l = PL_copy_term_ref(tcols), h = PL_new_term_ref();
  if ( !PL_get_integer(tw, &w) || w < 1 ) return FALSE;
  while( PL_get_list(l, h, l) )
  { column *c;
    if ( !get_column_raw(h, &c) ) return FALSE;
    if ( c->cnt[T_NUM] + c->cnt[T_U] + c->cnt[T_UNDEF] != c->n ) return FALSE;
    if ( c->cnt[T_NUM] > 0 && c->k != w ) return FALSE;
    n += c->n*(size_t)w;
  }
  if ( !(r = malloc(sizeof(frows) + (n ? n : 1)*sizeof(double))) )
    return PL_resource_error("memory");
  r->n = n;
  l = PL_copy_term_ref(tcols);
  while( PL_get_list(l, h, l) )
  { column *c;
    if ( !get_column_raw(h, &c) ) { free(r); return FALSE; }
    for(size_t i=0; i<c->n; i++)
    { size_t ii = CI(c, i);
      if ( c->tag[ii] == T_NUM )
	memcpy(&r->v[j], &c->f[ii*(size_t)w], sizeof(double)*(size_t)w);
      else
	for(int q=0; q<w; q++) r->v[j+(size_t)q] = NAN;
      j += (size_t)w;
    }
  }
  count_bytes(sizeof(frows) + n*sizeof(double));
  if ( !PL_unify_blob(out, r, sizeof(*r), &frows_blob) ) { free(r); return FALSE; }
  return TRUE;
}

/* col_floats_into(+Rows, +Address, +Capacity, -N): the N doubles of Rows
   (col_pack_rows/3's) copied to the memory at Address, which holds
   Capacity doubles (a numpy array's, from the Python bridge); fails,
   copying nothing, if N > Capacity */
static foreign_t
col_floats_into(term_t tr, term_t ta, term_t tcap, term_t tn)
{ void *data; PL_blob_t *type;
  int64_t addr, cap;
  frows *r;
  if ( !PL_get_blob(tr, &data, NULL, &type) || type != &frows_blob )
    return PL_type_error("ddc_floats", tr);
  r = data;
  if ( !PL_get_int64_ex(ta, &addr) || !PL_get_int64_ex(tcap, &cap) ) return FALSE;
  if ( addr == 0 || cap < 0 || r->n > (size_t)cap ) return FALSE;
  memcpy((void*)(intptr_t)addr, r->v, r->n*sizeof(double));
  return PL_unify_int64(tn, (int64_t)r->n);
}

/* Lists of floats to and from C arrays (the weights' passes, rows read as a list). */
static int
get_float_list(term_t l, size_t n, double *v)
{ term_t tail = PL_copy_term_ref(l), h = PL_new_term_ref();
  size_t i = 0;
  while( PL_get_list(tail, h, tail) )
  { if ( i == n || !PL_get_float(h, &v[i]) ) return FALSE;
    i++;
  }
  return i == n && PL_get_nil(tail);
}

static int
unify_float_list(term_t out, const double *v, size_t n)
{ term_t l = PL_new_term_ref(), h = PL_new_term_ref();
  PL_put_nil(l);
  for(size_t j=n; j-- > 0; )
    if ( !PL_put_float(h, v[j]) || !PL_cons_list(l, h, l) ) return FALSE;
  return PL_unify(out, l);
}

/* col_floats_list(+Rows, -Floats): the doubles of Rows as a list */
static foreign_t
col_floats_list(term_t tr, term_t out)
{ void *data; PL_blob_t *type;
  frows *r;
  if ( !PL_get_blob(tr, &data, NULL, &type) || type != &frows_blob )
    return PL_type_error("ddc_floats", tr);
  r = data;
  return unify_float_list(out, r->v, r->n);
}

/* col_weights_update(+LW0, +Step, -LW, -Inc, -ESS, -Infinite): the fast path of
   ddc_weights:weights_update/6 (prolog/ddc/filter/ddc_weights.pl, where the rules are
   written and commented), the same operations in the same order on doubles, so the same
   results; it fails, and the Prolog passes run (and raise what they raise), where the lists
   are not of numbers of the same length or a sum of two finite weights overflows. */
static foreign_t
col_weights_update(term_t tl0, term_t ts, term_t tlw, term_t tinc, term_t tess, term_t tinf)
{ size_t n;
  double *l0, *st, *c, max = -INFINITY, inc, ess;
  int infinite = FALSE, rc = FALSE;
  if ( PL_skip_list(tl0, 0, &n) != PL_LIST || n == 0 ) return FALSE;
  if ( !(l0 = malloc(3*n*sizeof(double))) ) return PL_resource_error("memory");
  st = l0 + n; c = st + n;
  if ( !get_float_list(tl0, n, l0) || !get_float_list(ts, n, st) ) goto out;
  for(size_t i=0; i<n; i++)                       /* combine/5 */
  { double l = st[i];
    if ( l == l && l > -INFINITY && l0[i] > -INFINITY )
    { if ( l == INFINITY ) c[i] = l;
      else
      { c[i] = l0[i] + l;
        if ( isinf(c[i]) ) goto out;             /* (Prolog raises float_overflow) */
      }
    } else
      c[i] = -INFINITY;
    if ( c[i] > max ) max = c[i];
  }
  if ( max == INFINITY )                          /* keep_infinite/2 */
  { infinite = TRUE;
    for(size_t i=0; i<n; i++) c[i] = c[i] == INFINITY ? 0.0 : -INFINITY;
    max = 0.0;
  }
  if ( max == -INFINITY )
    inc = max;
  else
  { double sum = 0.0;                             /* sum_exp/4, left to right */
    for(size_t i=0; i<n; i++)
      if ( c[i] != -INFINITY ) sum = sum + exp(c[i] - max);
    inc = max + log(sum);
  }
  if ( inc == -INFINITY )
  { ess = 0.0;
    rc = PL_unify(tlw, tl0);
  } else
  { double s = 0.0;                               /* normalise/5 */
    for(size_t i=0; i<n; i++)
      if ( c[i] != -INFINITY )
      { double w;
        c[i] = c[i] - inc;
        w = exp(c[i]);
        s = s + w*w;
      }
    ess = 1 / s;
    rc = unify_float_list(tlw, c, n);
  }
  rc = rc && PL_unify_float(tinc, inc) && PL_unify_float(tess, ess) &&
       PL_unify_atom_chars(tinf, infinite ? "true" : "false");
out:
  free(l0);
  return rc;
}

/* col_systematic_indices(+LogWeights, +U, -Indices): the fast path of a systematic
   resampling by ddc_weights.pl's rules (resample_log_weights/5 there: the weights exp(L),
   0.0 for -inf, the positions (U+k)/N, the walk over the cumulative weights), the same
   operations in the same order, so the same indices; fails where LogWeights is not a list
   of numbers or U not a number. */
static foreign_t
col_systematic_indices(term_t tlw, term_t tu, term_t out)
{ size_t n;
  double *w, u, c0 = 0.0;
  int rc = FALSE;
  if ( PL_skip_list(tlw, 0, &n) != PL_LIST || n == 0 || !PL_get_float(tu, &u) ) return FALSE;
  if ( !(w = malloc(n*sizeof(double))) ) return PL_resource_error("memory");
  if ( get_float_list(tlw, n, w) )
  { size_t *idx = malloc(n*sizeof(size_t)), i = 0, last = n-1;
    if ( !idx ) { free(w); return PL_resource_error("memory"); }
    for(size_t j=0; j<n; j++) w[j] = w[j] == -INFINITY ? 0.0 : exp(w[j]);
    for(size_t k=0; k<n; k++)
    { double p = (u + (double)k) / (double)n;
      for(;;)
      { double c;
        if ( i == last ) { idx[k] = last; break; }
        c = c0 + w[i];
        if ( c > p ) { idx[k] = i; break; }
        i++; c0 = c;
      }
    }
    { term_t l = PL_new_term_ref(), h = PL_new_term_ref();
      PL_put_nil(l);
      rc = TRUE;
      for(size_t j=n; j-- > 0 && rc; )
        rc = PL_put_int64(h, (int64_t)idx[j]) && PL_cons_list(l, h, l);
      rc = rc && PL_unify(out, l);
    }
    free(idx);
  }
  free(w);
  return rc;
}

/* col_status(+C, -S): open (a cell not drawn), same(V) (every cell V),
   defined (values, not all the same), mixed (some '$undef') */
static foreign_t
col_status(term_t tc, term_t ts)
{ column *c = NULL;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( c->n == 0 ) return FALSE;
  if ( c->cnt[T_U] > 0 ) return PL_unify_atom(ts, ATOM_open);
  if ( c->uni )
  { term_t v = PL_new_term_ref();
    return put_cell(v, c, 0) && PL_unify_term(ts, PL_FUNCTOR, FUNCTOR_same1, PL_TERM, v);
  }
  { int same = TRUE, undef = FALSE;
    for(size_t i=0; i<c->n; i++)
    { if ( c->tag[i] == T_U ) return PL_unify_atom(ts, ATOM_open);
      if ( c->tag[i] == T_UNDEF ) undef = TRUE;
      if ( same && i > 0 && !same_cell(c, i, c, 0) ) same = FALSE;
    }
    if ( same )
    { term_t v = PL_new_term_ref();
      return put_cell(v, c, 0) &&
	     PL_unify_term(ts, PL_FUNCTOR, FUNCTOR_same1, PL_TERM, v);
    }
    return PL_unify_atom(ts, undef ? ATOM_mixed : ATOM_defined);
  }
}

/* col_all_same(+Ps, +C, +I0): every particle of Ps has particle I0's value */
static foreign_t
col_all_same(term_t ps, term_t tc, term_t ti)
{ column *c = NULL; size_t i0;
  pview p;
  int rc = TRUE;
  if ( !get_column_raw(tc, &c) || !get_index(ti, c, &i0) ) return FALSE;
  if ( !get_view(ps, c->n, &p) ) return FALSE;
  if ( c->uni ) { free_view(&p); return TRUE; }
  for(size_t j=0; j<p.n && rc; j++)
    rc = same_cell(c, p.v[j], c, i0);
  free_view(&p);
  return rc;
}

/* col_num_arity(+C, -K): the arity of the column's number tuples when
   every cell holds one (fails otherwise) */
static foreign_t
col_num_arity(term_t tc, term_t tk)
{ column *c = NULL;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( c->k == 0 || c->cnt[T_NUM] != c->n ) return FALSE;
  return PL_unify_integer(tk, c->k);
}

/* A resampling's sources for one group: for each of its n particles the
   group g (1-based) and the particle l (0-based) of that group it copies
   (col_sources/3 makes them; a list of G-L pairs, 1-based, is read the
   same way) */
typedef struct gplan { size_t n; uint32_t gl[]; } gplan;

static PL_blob_t gplan_blob =
{ .magic   = PL_BLOB_MAGIC,
  .flags   = PL_BLOB_NOCOPY|PL_BLOB_UNIQUE,
  .name    = "ddc_sources",
  .release = release_counted,
  .write   = write_counted
};

/* get_plan(t, &p, &own): the sources t (a blob, or a list of G-L pairs,
   read into an owned plan); FALSE (a type error) if it is neither */
static int
get_plan(term_t t, gplan **pp, int *own)
{ void *data; PL_blob_t *type;
  size_t n;
  *own = FALSE;
  if ( PL_get_blob(t, &data, NULL, &type) && type == &gplan_blob )
  { *pp = data;
    return TRUE;
  }
  if ( PL_skip_list(t, 0, &n) != PL_LIST ) return PL_type_error("list", t);
  { gplan *p = malloc(sizeof(gplan) + (n ? 2*n : 1)*sizeof(uint32_t));
    term_t l = PL_copy_term_ref(t), h = PL_new_term_ref(), a = PL_new_term_ref();
    if ( !p ) return PL_resource_error("memory");
    p->n = n;
    for(size_t j=0; PL_get_list(l, h, l); j++)
    { int64_t g, li;
      if ( !PL_is_functor(h, FUNCTOR_minus2) ) goto type;
      _PL_get_arg(1, h, a); if ( !PL_get_int64_ex(a, &g) ) { free(p); return FALSE; }
      _PL_get_arg(2, h, a); if ( !PL_get_int64_ex(a, &li) ) { free(p); return FALSE; }
      if ( g < 1 || li < 1 || g > (int64_t)UINT32_MAX || li > (int64_t)UINT32_MAX ) goto type;
      p->gl[2*j] = (uint32_t)g; p->gl[2*j+1] = (uint32_t)(li-1);
    }
    *pp = p; *own = TRUE;
    return TRUE;
  type:
    free(p);
    return PL_domain_error("group_index_pair", t);
  }
}

/* col_plan_size(+Sources, -N): the number of particles of a group's
   sources (col_sources/3's) */
static foreign_t
col_plan_size(term_t t, term_t tn)
{ void *data; PL_blob_t *type;
  size_t n;
  if ( PL_get_blob(t, &data, NULL, &type) && type == &gplan_blob )
    return PL_unify_int64(tn, (int64_t)((gplan*)data)->n);
  if ( PL_skip_list(t, 0, &n) != PL_LIST ) return PL_type_error("list", t);
  return PL_unify_int64(tn, (int64_t)n);
}

/* col_gather(+Sources, +Pairs, -C): C's particle j is particle L of the
   G-th source of the j-th pair G-L (Pairs a group's sources, col_sources/3's
   blob, or a list of G-L pairs, 1-based; a source '$none' gives '$u') */
static foreign_t
col_gather(term_t srcs, term_t pairs, term_t tc)
{ size_t nsrc;
  column **src;
  column *c = NULL;
  gplan *p = NULL;
  int own;
  if ( !PL_skip_list(srcs, 0, &nsrc) ) return PL_type_error("list", srcs);
  if ( !get_plan(pairs, &p, &own) ) return FALSE;
  if ( !(src = calloc(nsrc ? nsrc : 1, sizeof(column*))) )
  { if ( own ) free(p);
    return PL_resource_error("memory");
  }
  { term_t l = PL_copy_term_ref(srcs), h = PL_new_term_ref();
    for(size_t g=0; PL_get_list(l, h, l); g++)
    { atom_t a;
      if ( PL_get_atom(h, &a) && a == ATOM_none )
	src[g] = NULL;			/* '$none' */
      else if ( !get_column_raw(h, &src[g]) ) goto error;
    }
  }
  if ( !(c = new_column(p->n)) ) { PL_resource_error("memory"); goto error; }
  for(size_t j=0; j<p->n; j++)
  { uint32_t g = p->gl[2*j], li = p->gl[2*j+1];
    column *s;
    if ( g < 1 || (size_t)g > nsrc ) goto type;
    if ( !(s = src[g-1]) ) continue;			/* (T_U) */
    if ( (size_t)li >= s->n ) goto type;
    if ( !copy_cell(c, j, s, li) ) goto error;
  }
  free(src);
  if ( own ) free(p);
  if ( !unify_column(tc, c) ) { free_cells(c); return FALSE; }
  return TRUE;
type:
  PL_domain_error("group_index_pair", pairs);
error:
  free(src);
  if ( own ) free(p);
  if ( c ) free_cells(c);
  return FALSE;
}

		 /*******************************
		 *        RANDOM NUMBERS        *
		 *******************************/

typedef struct rng { uint64_t s[4]; } rng;

static uint64_t
splitmix64(uint64_t *x)
{ uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

static void
rng_seed(rng *r, uint64_t seed)
{ for(int i=0; i<4; i++) r->s[i] = splitmix64(&seed);
}

static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

static inline uint64_t
rng_next(rng *r)
{ uint64_t *s = r->s;
  const uint64_t result = s[0] + s[3];
  const uint64_t t = s[1] << 17;
  s[2] ^= s[0]; s[3] ^= s[1]; s[1] ^= s[2]; s[0] ^= s[3];
  s[2] ^= t;
  s[3] = rotl(s[3], 45);
  return result;
}

/* a uniform in (0, 1] */
static inline double
rng_uniform(rng *r)
{ return ((rng_next(r) >> 11) + 1) * 0x1.0p-53;
}

/* Standard normals by the ziggurat method (Marsaglia and Tsang, with
   Doornik's layers: the density under 128 rectangles of equal area and a
   tail; a draw is nearly always one 64-bit number, a multiplication and a
   comparison, where Box-Muller takes a logarithm, a square root and two
   trigonometric functions per two draws).  The layers' edges are computed
   once, when the library is loaded (zig_init/0). */

#define ZIG_N 128
#define ZIG_R 3.442619855899			/* the start of the tail */
#define ZIG_V 9.91256303526217e-3		/* each layer's area */

static double zig_x[ZIG_N+1];			/* the layers' right edges */
static double zig_ratio[ZIG_N];			/* zig_x[i+1]/zig_x[i] */

static void
zig_init(void)
{ double f = exp(-0.5*ZIG_R*ZIG_R);
  zig_x[0] = ZIG_V/f;				/* (the base layer's width with its tail) */
  zig_x[1] = ZIG_R;
  zig_x[ZIG_N] = 0.0;
  for(int i=2; i<ZIG_N; i++)
  { zig_x[i] = sqrt(-2.0*log(ZIG_V/zig_x[i-1] + f));
    f = exp(-0.5*zig_x[i]*zig_x[i]);
  }
  for(int i=0; i<ZIG_N; i++) zig_ratio[i] = zig_x[i+1]/zig_x[i];
}

/* a standard normal's tail beyond ZIG_R (Marsaglia's method), negated if neg */
static double
zig_tail(rng *r, int neg)
{ double x, y;
  do
  { x = log(rng_uniform(r))/ZIG_R;
    y = log(rng_uniform(r));
  } while( -2.0*y < x*x );
  return neg ? x - ZIG_R : ZIG_R - x;
}

/* a standard normal */
static inline double
rng_normal(rng *r)
{ for(;;)
  { uint64_t b = rng_next(r);
    int i = (int)((b >> 4) & (ZIG_N-1));	/* (not the lowest bits: xoshiro256+'s weakest) */
    double u = 2.0*((double)(b >> 11) * 0x1.0p-53) - 1.0;	/* [-1, 1) */
    double x, f0, f1;
    if ( fabs(u) < zig_ratio[i] ) return u*zig_x[i];	/* (inside the layer's rectangle) */
    if ( i == 0 ) return zig_tail(r, u < 0.0);
    x = u*zig_x[i];
    f0 = exp(-0.5*(zig_x[i]*zig_x[i] - x*x));
    f1 = exp(-0.5*(zig_x[i+1]*zig_x[i+1] - x*x));
    if ( f1 + rng_uniform(r)*(f0 - f1) < 1.0 ) return x;
  }
}

static int
get_seed(term_t t, rng *r)
{ int64_t s;
  if ( !PL_get_int64_ex(t, &s) ) return FALSE;
  rng_seed(r, (uint64_t)s);
  return TRUE;
}

		 /*******************************
		 *       GAUSSIAN OVER BATCH    *
		 *******************************/

/* get_factor(t, L, &k): t is chol(L11, L21, L22, L31, L32, L33) (k = 3)
   or sd(SD) (k = 1) */
static int
get_factor(term_t t, double *L, int *kp)
{ atom_t name; size_t arity;
  term_t a = PL_new_term_ref();
  if ( !PL_get_name_arity(t, &name, &arity) ) return FALSE;
  if ( arity != 6 && arity != 1 ) return FALSE;
  for(size_t j=0; j<arity; j++)
  { _PL_get_arg(j+1, t, a);
    if ( !PL_get_float(a, &L[j]) ) return FALSE;
  }
  *kp = arity == 6 ? 3 : 1;
  return TRUE;
}

/* get_batch(ps, c, &p): the batch ps of particles of c (a view of its
   0-based indices); FALSE if it is not one */
static int
get_batch(term_t ps, column *c, pview *p)
{ return get_view(ps, c->n, p);
}

/* col_draw_gauss(+Ps, +MeanC, +Factor, +Out, +Seed) is semidet: each
   particle of Ps not drawn yet in Out gets a draw of the gaussian whose
   mean is its value in MeanC and whose covariance has the Cholesky factor
   Factor.  Fails, changing nothing, if a mean is not a number tuple of the
   factor's dimension. */
static foreign_t
col_draw_gauss(term_t ps, term_t tm, term_t tf, term_t to, term_t ts)
{ column *mc, *out;
  double L[6];
  int k;
  size_t m;
  const uint32_t *idx;
  pview pv;
  rng r;

  if ( !get_column_raw(tm, &mc) || !get_column(to, &out) ) return FALSE;
  if ( !get_factor(tf, L, &k) || !get_seed(ts, &r) ) return FALSE;
  if ( mc->k != k || mc->n != out->n ) return FALSE;
  if ( out->k != 0 && out->k != k ) return FALSE;
  if ( !get_batch(ps, out, &pv) ) return FALSE;
  idx = pv.v; m = pv.n;
  for(size_t j=0; j<m; j++)
  { if ( out->tag[idx[j]] == T_U && mc->tag[CI(mc, idx[j])] != T_NUM )
    { free_view(&pv); return FALSE; }
  }
  if ( out->k == 0 && !set_k(out, k) ) { free_view(&pv); return FALSE; }
  for(size_t j=0; j<m; j++)
  { size_t i = idx[j];
    if ( out->tag[i] != T_U ) continue;
    { const double *mu = &mc->f[CI(mc, i)*(size_t)k];
      double *x = &out->f[i*(size_t)k];
      if ( k == 3 )
      { double z1 = rng_normal(&r), z2 = rng_normal(&r), z3 = rng_normal(&r);
	x[0] = mu[0] + L[0]*z1;
	x[1] = mu[1] + L[1]*z1 + L[2]*z2;
	x[2] = mu[2] + L[3]*z1 + L[4]*z2 + L[5]*z3;
      } else
	x[0] = mu[0] + L[0]*rng_normal(&r);
      SET_TAG(out, i, T_NUM);
    }
  }
  free_view(&pv);
  return TRUE;
}

/* gauss_log_density(v, mu, L, k, ln): the log density at v of the gaussian
   of mean mu, Cholesky factor L (k = 3 or 1) and log normaliser ln */
static double
gauss_log_density(const double *v, const double *mu, const double *L, int k, double ln)
{ if ( k == 3 )
  { double y1 = (v[0] - mu[0])/L[0];
    double y2 = (v[1] - mu[1] - L[1]*y1)/L[2];
    double y3 = (v[2] - mu[2] - L[3]*y1 - L[4]*y2)/L[5];
    return -0.5*(y1*y1 + y2*y2 + y3*y3) + ln;
  } else
  { double y = (v[0] - mu[0])/L[0];
    return -0.5*y*y + ln;
  }
}

static inline void
add_log(column *lw, size_t i, double lp)
{ double l0 = lw->f[i];
  if ( l0 > -1.0e308 && lp > -1.0e308 ) lw->f[i] = l0 + lp;
  else if ( l0 < -1.0e308 ) ;
  else lw->f[i] = lp;
}

/* col_weigh_gauss(+Ps, +MeanC, +Factor, +LogNorm, +Value, +Done, +LW) is
   semidet: each particle of Ps not weighed yet (Done's '$u') is marked
   done and its log weight in LW gets the log density of Value (a number
   tuple) under the gaussian of mean its value in MeanC and Cholesky factor
   Factor.  Fails, changing nothing, if a mean or Value is not a number
   tuple of the factor's dimension, or LW does not hold floats. */
static foreign_t
col_weigh_gauss(term_t ps, term_t tm, term_t tf, term_t tln, term_t tv,
		term_t td, term_t tlw)
{ column *mc, *done, *lw;
  double L[6], v[MAX_K], ln;
  int k;
  size_t m;
  const uint32_t *idx;
  pview pv;

  if ( !get_column_raw(tm, &mc) || !get_column_raw(td, &done) || !get_column_raw(tlw, &lw) )
    return FALSE;
  if ( !get_factor(tf, L, &k) || !PL_get_float(tln, &ln) ) return FALSE;
  if ( float_tuple(tv, v, MAX_K) != k || mc->k != k || lw->k != 1 ) return FALSE;
  if ( mc->n != lw->n || done->n != lw->n ) return FALSE;
  if ( !get_batch(ps, lw, &pv) ) return FALSE;
  idx = pv.v; m = pv.n;
  for(size_t j=0; j<m; j++)
  { size_t i = idx[j];
    if ( done->tag[CI(done, i)] == T_U &&
	 (mc->tag[CI(mc, i)] != T_NUM || lw->tag[CI(lw, i)] != T_NUM) )
    { free_view(&pv); return FALSE; }
  }
  if ( mc->uni && done->uni && lw->uni && m == lw->n && done->tag[0] == T_U )
  { /* (every particle, one mean, one log weight so far: one log weight after) */
    term_t t = PL_new_term_ref();
    free_view(&pv);
    return PL_put_atom(t, ATOM_done) && set_uniform(done, t) &&
	   (add_log(lw, 0, gauss_log_density(v, mc->f, L, k, ln)), TRUE);
  }
  if ( !expand(done) || !expand(lw) || !ensure_x(done) ) { free_view(&pv); return FALSE; }
  for(size_t j=0; j<m; j++)
  { size_t i = idx[j];
    if ( done->tag[i] != T_U ) continue;
    PL_register_atom(ATOM_done);
    done->x[i] = (uintptr_t)ATOM_done;
    SET_TAG(done, i, T_ATOM);
    add_log(lw, i, gauss_log_density(v, &mc->f[CI(mc, i)*(size_t)k], L, k, ln));
  }
  free_view(&pv);
  return TRUE;
}


		 /*******************************
		 *     ARITHMETIC OVER BATCH    *
		 *******************************/

/* A loop of arithmetic over a batch, compiled by the Prolog side
   (ddc_batch_col.pl, col_vm_program/4) into instructions over registers
   of floats, run for each particle:

     ld(R, J, C, K)    R is component C of the particle's K-tuple in column J
     cst(R, F)         R is the number F
     op(R, Op, A, B)   R is A Op B (Op: +, -, *, /, **, atan2)
     fn(R, F, A)       R is F(A) (F: -, sqrt, exp, log, sin, cos, tan, atan,
                       tanh, abs)

   Any result that is not a finite float (a division by zero, the log of a
   negative number: an error in Prolog), a cell that is not a tuple of the
   expected arity, abandons the loop (the call fails, nothing written):
   the caller runs it in Prolog, which raises the error or gives the
   particle its answer. */

enum { I_LD, I_CST, I_ADD, I_SUB, I_MUL, I_DIV, I_POW, I_ATAN2,
       I_NEG, I_SQRT, I_EXP, I_LOG, I_SIN, I_COS, I_TAN, I_ATAN, I_TANH, I_ABS };

typedef struct insn { int op, r, a, b, j, c, k; double f; } insn;

#define MAX_REGS 64
#define MAX_COLS 32

typedef struct vm
{ insn    *code;
  int      ncode;
  column  *col[MAX_COLS];
  int      ncol;
} vm;

static int
get_int_arg(int n, term_t t, int *ip)
{ term_t a = PL_new_term_ref();
  _PL_get_arg(n, t, a);
  return PL_get_integer(a, ip);
}

static int
op_code(atom_t a, int binary, int *op)
{ const char *s = PL_atom_chars(a);
  if ( binary )
  { if ( !strcmp(s, "+") ) *op = I_ADD;
    else if ( !strcmp(s, "-") ) *op = I_SUB;
    else if ( !strcmp(s, "*") ) *op = I_MUL;
    else if ( !strcmp(s, "/") ) *op = I_DIV;
    else if ( !strcmp(s, "**") ) *op = I_POW;
    else if ( !strcmp(s, "atan2") ) *op = I_ATAN2;
    else return FALSE;
  } else
  { if ( !strcmp(s, "-") ) *op = I_NEG;
    else if ( !strcmp(s, "sqrt") ) *op = I_SQRT;
    else if ( !strcmp(s, "exp") ) *op = I_EXP;
    else if ( !strcmp(s, "log") ) *op = I_LOG;
    else if ( !strcmp(s, "sin") ) *op = I_SIN;
    else if ( !strcmp(s, "cos") ) *op = I_COS;
    else if ( !strcmp(s, "tan") ) *op = I_TAN;
    else if ( !strcmp(s, "atan") ) *op = I_ATAN;
    else if ( !strcmp(s, "tanh") ) *op = I_TANH;
    else if ( !strcmp(s, "abs") ) *op = I_ABS;
    else return FALSE;
  }
  return TRUE;
}

static int
reg_ok(int r) { return r >= 0 && r < MAX_REGS; }

/* vm_load(cols, code, &vm): the program; FALSE (no exception) if it is
   not one this loop runs */
static int
vm_load(term_t cols, term_t code, vm *m)
{ size_t n;
  term_t l, h;
  m->ncol = 0; m->code = NULL;
  l = PL_copy_term_ref(cols); h = PL_new_term_ref();
  while( PL_get_list(l, h, l) )
  { void *data; PL_blob_t *type;
    if ( m->ncol >= MAX_COLS ) return FALSE;
    if ( !PL_get_blob(h, &data, NULL, &type) || type != &column_blob ) return FALSE;
    m->col[m->ncol++] = data;
  }
  if ( !PL_skip_list(code, 0, &n) || n == 0 ) return FALSE;
  if ( !(m->code = malloc(n*sizeof(insn))) ) return FALSE;
  m->ncode = (int)n;
  l = PL_copy_term_ref(code);
  for(int i=0; PL_get_list(l, h, l); i++)
  { insn *in = &m->code[i];
    atom_t name, a; size_t arity;
    term_t t = PL_new_term_ref();
    memset(in, 0, sizeof(*in));
    if ( !PL_get_name_arity(h, &name, &arity) ) goto bad;
    if ( !get_int_arg(1, h, &in->r) || !reg_ok(in->r) ) goto bad;
    if ( !strcmp(PL_atom_chars(name), "ld") && arity == 4 )
    { in->op = I_LD;
      if ( !get_int_arg(2, h, &in->j) || !get_int_arg(3, h, &in->c) ||
	   !get_int_arg(4, h, &in->k) ) goto bad;
      if ( in->j < 0 || in->j >= m->ncol || in->k < 1 || in->c < 0 || in->c >= in->k ) goto bad;
      if ( m->col[in->j]->k != in->k ) goto bad;
    } else if ( !strcmp(PL_atom_chars(name), "cst") && arity == 2 )
    { in->op = I_CST;
      _PL_get_arg(2, h, t);
      if ( !PL_get_float(t, &in->f) ) goto bad;
    } else if ( !strcmp(PL_atom_chars(name), "op") && arity == 4 )
    { _PL_get_arg(2, h, t);
      if ( !PL_get_atom(t, &a) || !op_code(a, TRUE, &in->op) ) goto bad;
      if ( !get_int_arg(3, h, &in->a) || !get_int_arg(4, h, &in->b) ||
	   !reg_ok(in->a) || !reg_ok(in->b) ) goto bad;
    } else if ( !strcmp(PL_atom_chars(name), "fn") && arity == 3 )
    { _PL_get_arg(2, h, t);
      if ( !PL_get_atom(t, &a) || !op_code(a, FALSE, &in->op) ) goto bad;
      if ( !get_int_arg(3, h, &in->a) || !reg_ok(in->a) ) goto bad;
    } else
      goto bad;
  }
  return TRUE;
bad:
  free(m->code); m->code = NULL;
  return FALSE;
}

/* vm_run(m, i, r): the program for particle i: VM_OK, VM_SKIP (a cell
   that the pattern does not unify with: '$u', '$undef' or an atom, as the
   Prolog loop skips the particle) or VM_ABANDON (any other term, an
   arithmetic error: the caller runs the loop in Prolog) */
#define VM_OK       1
#define VM_ABANDON  0
#define VM_SKIP    -1

static int
vm_run(const vm *m, size_t i, double *r)
{ for(int p=0; p<m->ncode; p++)
  { const insn *in = &m->code[p];
    double x;
    switch(in->op)
    { case I_LD:
      { const column *c = m->col[in->j];
	size_t ii = CI(c, i);
	if ( c->tag[ii] != T_NUM )	/* (a tuple pattern unifies with no atom or list:
					    the particle is skipped; a variable with
					    anything: an error in Prolog) */
	  return in->k > 1 && c->tag[ii] != T_TERM ? VM_SKIP : VM_ABANDON;
	r[in->r] = c->f[ii*(size_t)in->k + (size_t)in->c];
	continue;
      }
      case I_CST: r[in->r] = in->f; continue;
      case I_ADD: x = r[in->a] + r[in->b]; break;
      case I_SUB: x = r[in->a] - r[in->b]; break;
      case I_MUL: x = r[in->a] * r[in->b]; break;
      case I_DIV: if ( r[in->b] == 0.0 ) return VM_ABANDON; x = r[in->a] / r[in->b]; break;
      case I_POW: x = pow(r[in->a], r[in->b]); break;
      case I_ATAN2: x = atan2(r[in->a], r[in->b]); break;
      case I_NEG: x = -r[in->a]; break;
      case I_SQRT: if ( r[in->a] < 0.0 ) return VM_ABANDON; x = sqrt(r[in->a]); break;
      case I_EXP: x = exp(r[in->a]); break;
      case I_LOG: if ( r[in->a] <= 0.0 ) return VM_ABANDON; x = log(r[in->a]); break;
      case I_SIN: x = sin(r[in->a]); break;
      case I_COS: x = cos(r[in->a]); break;
      case I_TAN: x = tan(r[in->a]); break;
      case I_ATAN: x = atan(r[in->a]); break;
      case I_TANH: x = tanh(r[in->a]); break;
      case I_ABS: x = fabs(r[in->a]); break;
      default: return VM_ABANDON;
    }
    if ( !isfinite(x) ) return VM_ABANDON;
    r[in->r] = x;
  }
  return VM_OK;
}

enum { C_LT, C_GT, C_LE, C_GE, C_EQ, C_NE };

static int
cmp_code(atom_t a, int *op)
{ const char *s = PL_atom_chars(a);
  if ( !strcmp(s, "<") ) *op = C_LT;
  else if ( !strcmp(s, ">") ) *op = C_GT;
  else if ( !strcmp(s, "=<") ) *op = C_LE;
  else if ( !strcmp(s, ">=") ) *op = C_GE;
  else if ( !strcmp(s, "=:=") ) *op = C_EQ;
  else if ( !strcmp(s, "=\\=") ) *op = C_NE;
  else return FALSE;
  return TRUE;
}

/* vm_uniform(m): every column m reads is uniform: the loop gives every
   particle the same answer */
static int
vm_uniform(const vm *m)
{ for(int j=0; j<m->ncol; j++)
    if ( !m->col[j]->uni ) return FALSE;
  return TRUE;
}

/* run_test(m, op, a, b, ps, out): Out the particles of Ps in which
   register a op register b after m's code (op a comparison); FALSE if the
   loop is abandoned (above) */
static int
run_test(const vm *m, int op, int a, int b, term_t ps, term_t out)
{ double r[MAX_REGS];
  size_t np, nout = 0;
  const uint32_t *idx;
  pview pv;
  char *hold;
  int uni;

  if ( m->ncol == 0 ) return FALSE;
  for(int j=1; j<m->ncol; j++)
    if ( m->col[j]->n != m->col[0]->n ) return FALSE;
  if ( !get_batch(ps, m->col[0], &pv) ) return FALSE;
  idx = pv.v; np = pv.n;
  if ( !(hold = malloc(np ? np : 1)) ) { free_view(&pv); return FALSE; }
  uni = vm_uniform(m);
  for(size_t j=0; j<np; j++)
  { int h, rc;
    if ( j > 0 && uni ) { hold[j] = hold[0]; nout += (size_t)hold[0]; continue; }
    rc = vm_run(m, idx[j], r);
    if ( rc == VM_ABANDON ) { free(hold); free_view(&pv); return FALSE; }
    if ( rc == VM_SKIP ) { hold[j] = 0; continue; }
    switch(op)
    { case C_LT: h = r[a] <  r[b]; break;
      case C_GT: h = r[a] >  r[b]; break;
      case C_LE: h = r[a] <= r[b]; break;
      case C_GE: h = r[a] >= r[b]; break;
      case C_EQ: h = r[a] == r[b]; break;
      default:   h = r[a] != r[b]; break;
    }
    hold[j] = (char)h;
    nout += h;
  }
  { int rc = unify_selected(out, ps, &pv, hold, nout);
    free(hold); free_view(&pv);
    return rc;
  }
}

/* col_vm_test(+Ps, +Cols, +Code, +Op, +A, +B, -Out) is semidet: Out the
   particles of Ps in which register A Op register B after Code (Op a
   comparison); fails if the loop is abandoned (above) */
static foreign_t
col_vm_test(term_t ps, term_t cols, term_t code, term_t top, term_t ta, term_t tb,
	    term_t out)
{ vm m;
  atom_t opa;
  int op, a, b, rc;

  if ( !PL_get_atom(top, &opa) || !cmp_code(opa, &op) ) return FALSE;
  if ( !PL_get_integer(ta, &a) || !PL_get_integer(tb, &b) || !reg_ok(a) || !reg_ok(b) )
    return FALSE;
  if ( !vm_load(cols, code, &m) ) return FALSE;
  rc = run_test(&m, op, a, b, ps, out);
  free(m.code);
  return rc;
}

/* run_instance(m, regs, k, ps, c): each particle of ps not drawn yet in c
   gets the tuple of the k registers regs after m's code; FALSE, writing
   nothing, if the loop is abandoned (above) */
static int
run_instance(const vm *m, const int *regs, int k, term_t ps, column *c)
{ double r[MAX_REGS], *buf;
  size_t np;
  const uint32_t *idx;
  pview pv;
  char *skip;

  if ( k == 0 || (c->k != 0 && c->k != k) ) return FALSE;
  for(int j=0; j<m->ncol; j++)
    if ( m->col[j]->n != c->n ) return FALSE;
  if ( !get_batch(ps, c, &pv) ) return FALSE;
  idx = pv.v; np = pv.n;
  if ( c->uni && c->tag[0] == T_U && np == c->n && vm_uniform(m) )
  { int rc = vm_run(m, 0, r);			/* (one value for every particle) */
    free_view(&pv);
    if ( rc == VM_ABANDON ) return FALSE;
    if ( rc == VM_SKIP ) return TRUE;
    if ( c->k == 0 && !set_k(c, k) ) return FALSE;
    for(int q=0; q<k; q++) c->f[q] = r[regs[q]];
    c->tag[0] = T_NUM;
    c->cnt[T_U] = 0; c->cnt[T_NUM] = c->n;
    c->cls_valid = 0;
    return TRUE;
  }
  if ( !expand(c) ) { free_view(&pv); return FALSE; }
  if ( !(buf = malloc((np ? np : 1)*(size_t)k*sizeof(double))) ) { free_view(&pv); return FALSE; }
  if ( !(skip = calloc(np ? np : 1, 1)) ) { free(buf); free_view(&pv); return FALSE; }
  for(size_t j=0; j<np; j++)
  { int rc;
    if ( c->tag[idx[j]] != T_U ) continue;
    if ( (rc=vm_run(m, idx[j], r)) == VM_ABANDON )
    { free(skip); free(buf); free_view(&pv); return FALSE; }
    if ( rc == VM_SKIP ) { skip[j] = 1; continue; }
    for(int q=0; q<k; q++) buf[j*(size_t)k+(size_t)q] = r[regs[q]];
  }
  if ( c->k == 0 && !set_k(c, k) ) { free(skip); free(buf); free_view(&pv); return FALSE; }
  for(size_t j=0; j<np; j++)
  { size_t i = idx[j];
    if ( c->tag[i] != T_U || skip[j] ) continue;
    memcpy(&c->f[i*(size_t)k], &buf[j*(size_t)k], sizeof(double)*(size_t)k);
    SET_TAG(c, i, T_NUM);
  }
  free(skip); free(buf); free_view(&pv);
  return TRUE;
}

/* col_vm_instance(+Ps, +Cols, +Code, +Regs, !C) is semidet: each particle
   of Ps not drawn yet in C gets the tuple of the registers Regs after
   Code; fails, writing nothing, if the loop is abandoned (above) */
static foreign_t
col_vm_instance(term_t ps, term_t cols, term_t code, term_t tregs, term_t tc)
{ vm m;
  column *c;
  int regs[MAX_K], k = 0, rc;

  if ( !get_column(tc, &c) ) return FALSE;
  { term_t l = PL_copy_term_ref(tregs), h = PL_new_term_ref();
    while( PL_get_list(l, h, l) )
    { if ( k >= MAX_K || !PL_get_integer(h, &regs[k]) || !reg_ok(regs[k]) ) return FALSE;
      k++;
    }
  }
  if ( k == 0 || (c->k != 0 && c->k != k) ) return FALSE;
  if ( !vm_load(cols, code, &m) ) return FALSE;
  rc = run_instance(&m, regs, k, ps, c);
  free(m.code);
  return rc;
}

/* col_copy_each(+Ps, +From, !C): each particle of Ps not drawn yet in C
   gets its value in From */
static foreign_t
col_copy_each(term_t ps, term_t tf, term_t tc)
{ column *from, *c;
  size_t np;
  const uint32_t *idx;
  pview pv;
  if ( !get_column_raw(tf, &from) || !get_column_raw(tc, &c) ) return FALSE;
  if ( from->n != c->n ) return FALSE;
  if ( !get_batch(ps, c, &pv) ) return FALSE;
  idx = pv.v; np = pv.n;
  if ( c->uni && c->tag[0] == T_U && from->uni && np == c->n )
  { term_t t = PL_new_term_ref();		/* (one value for every particle) */
    free_view(&pv);
    return put_cell(t, from, 0) && set_uniform(c, t);
  }
  if ( !expand(c) ) { free_view(&pv); return FALSE; }
  for(size_t j=0; j<np; j++)
  { if ( c->tag[idx[j]] == T_U && !copy_cell(c, idx[j], from, idx[j]) )
    { free_view(&pv); return FALSE; }
  }
  free_view(&pv);
  return TRUE;
}

		 /*******************************
		 *   LOOPS COMPILED FROM TERMS  *
		 *******************************/

/* The same loops, compiled here from the goal's own terms instead of from
   the Prolog side's instructions (ddc_batch_columns.pl's plan/3 and
   vm_expr/5: a goal's compilation in Prolog costs more than the loop over
   a thousand particles).  An expression is a number, pi or e, a column
   reference '$c'(C, P, V) (the particle's value V in column C: P is V, or
   a tuple of distinct variables one of which is V), a deferred expression
   '$x'(E), or one of the loop's operations over expressions.  Anything
   else (a variable, an atom, a reference whose pattern a partition bound)
   makes the compilation fail, and the caller takes the Prolog path. */

#define MAX_CODE 256

typedef struct vmc
{ vm	   m;				/* m.code is buf */
  insn	   buf[MAX_CODE];
  int	   nreg;
  term_t   xt[MAX_REGS];		/* deferred expressions compiled, */
  int	   xr[MAX_REGS], xf[MAX_REGS];	/* their registers and floatness */
  int	   nx;
  column  *lc[MAX_REGS];		/* loads made: column, component, arity */
  int	   lcomp[MAX_REGS], lk[MAX_REGS], lr[MAX_REGS];
  int	   nl;
} vmc;

static functor_t FUNCTOR_cref3, FUNCTOR_xref1;

static void
vmc_init(vmc *v)
{ v->m.code = v->buf; v->m.ncode = 0; v->m.ncol = 0;
  v->nreg = 0; v->nx = 0; v->nl = 0;
}

static insn *
vmc_emit(vmc *v, int op)
{ insn *in;
  if ( v->m.ncode >= MAX_CODE || v->nreg >= MAX_REGS ) return NULL;
  in = &v->buf[v->m.ncode++];
  memset(in, 0, sizeof(*in));
  in->op = op;
  in->r = v->nreg++;
  return in;
}

/* tuple_component(p, x, &c, &k): p is a tuple of k >= 2 distinct variables
   whose c-th (0-based) is x */
static int
tuple_component(term_t p, term_t x, int *cp, int *kp)
{ term_t el[MAX_K];
  term_t r = PL_copy_term_ref(p);
  int k = 0, c = -1;
  while( PL_is_functor(r, FUNCTOR_comma2) )
  { if ( k >= MAX_K-1 ) return FALSE;
    el[k] = PL_new_term_ref();
    _PL_get_arg(1, r, el[k]);
    _PL_get_arg(2, r, r);
    k++;
  }
  if ( k == 0 ) return FALSE;
  el[k++] = r;
  for(int i=0; i<k; i++)
  { if ( !PL_is_variable(el[i]) ) return FALSE;
    for(int j=0; j<i; j++) if ( PL_compare(el[i], el[j]) == 0 ) return FALSE;
    if ( PL_compare(el[i], x) == 0 ) c = i;
  }
  if ( c < 0 ) return FALSE;
  *cp = c; *kp = k;
  return TRUE;
}

static int compile_expr(vmc *v, term_t t, int *rp, int *fp, int depth);

static int
compile_ref(vmc *v, term_t t, int *rp, int *fp)
{ term_t a = PL_new_term_ref(), p = PL_new_term_ref(), x = PL_new_term_ref();
  void *data; PL_blob_t *type;
  column *c;
  int comp, k, j;
  _PL_get_arg(1, t, a); _PL_get_arg(2, t, p); _PL_get_arg(3, t, x);
  if ( !PL_get_blob(a, &data, NULL, &type) || type != &column_blob ) return FALSE;
  c = data;
  if ( !PL_is_variable(x) ) return FALSE;
  if ( PL_compare(p, x) == 0 ) { comp = 0; k = 1; }
  else if ( !tuple_component(p, x, &comp, &k) ) return FALSE;
  if ( c->k != k ) return FALSE;
  for(int q=0; q<v->nl; q++)
  { if ( v->lc[q] == c && v->lcomp[q] == comp && v->lk[q] == k )
    { *rp = v->lr[q]; *fp = TRUE;
      return TRUE;
    }
  }
  for(j=0; j<v->m.ncol && v->m.col[j] != c; j++) ;
  if ( j == v->m.ncol )
  { if ( j >= MAX_COLS ) return FALSE;
    v->m.col[v->m.ncol++] = c;
  }
  { insn *in = vmc_emit(v, I_LD);
    if ( !in || v->nl >= MAX_REGS ) return FALSE;
    in->j = j; in->c = comp; in->k = k;
    v->lc[v->nl] = c; v->lcomp[v->nl] = comp; v->lk[v->nl] = k; v->lr[v->nl] = in->r;
    v->nl++;
    *rp = in->r; *fp = TRUE;
    return TRUE;
  }
}

static int
compile_expr(vmc *v, term_t t, int *rp, int *fp, int depth)
{ atom_t name;
  size_t arity;
  if ( depth > 200 ) return FALSE;
  if ( PL_is_number(t) )
  { double f;
    insn *in;
    if ( PL_is_integer(t) )
    { int64_t i;
      if ( !PL_get_int64(t, &i) || i > ((int64_t)1<<53) || i < -((int64_t)1<<53) ) return FALSE;
      f = (double)i; *fp = FALSE;
    } else
    { if ( !PL_get_float(t, &f) ) return FALSE;
      *fp = TRUE;
    }
    if ( !(in = vmc_emit(v, I_CST)) ) return FALSE;
    in->f = f; *rp = in->r;
    return TRUE;
  }
  if ( PL_get_atom(t, &name) )
  { const char *sn = PL_atom_chars(name);
    insn *in;
    double f;
    if ( !strcmp(sn, "pi") ) f = 3.141592653589793;
    else if ( !strcmp(sn, "e") ) f = 2.718281828459045;
    else return FALSE;
    if ( !(in = vmc_emit(v, I_CST)) ) return FALSE;
    in->f = f; *rp = in->r; *fp = TRUE;
    return TRUE;
  }
  if ( !PL_get_name_arity(t, &name, &arity) ) return FALSE;
  if ( PL_is_functor(t, FUNCTOR_cref3) ) return compile_ref(v, t, rp, fp);
  if ( PL_is_functor(t, FUNCTOR_xref1) )
  { term_t e = PL_new_term_ref();
    for(int q=0; q<v->nx; q++)
    { if ( PL_compare(v->xt[q], t) == 0 )
      { *rp = v->xr[q]; *fp = v->xf[q];
	return TRUE;
      }
    }
    _PL_get_arg(1, t, e);
    if ( !compile_expr(v, e, rp, fp, depth+1) || v->nx >= MAX_REGS ) return FALSE;
    v->xt[v->nx] = PL_copy_term_ref(t); v->xr[v->nx] = *rp; v->xf[v->nx] = *fp;
    v->nx++;
    return TRUE;
  }
  if ( arity == 2 )
  { term_t a = PL_new_term_ref(), b = PL_new_term_ref();
    int op, ra, rb, fa, fb;
    insn *in;
    _PL_get_arg(1, t, a); _PL_get_arg(2, t, b);
    if ( !strcmp(PL_atom_chars(name), "atan") ) op = I_ATAN2;
    else if ( !op_code(name, TRUE, &op) ) return FALSE;
    if ( op == I_POW && PL_is_integer(b) )	/* (A*A: the same float as A**2) */
    { int64_t e;
      if ( PL_get_int64(b, &e) && e == 2 )
      { if ( !compile_expr(v, a, &ra, &fa, depth+1) || !(in = vmc_emit(v, I_MUL)) )
	  return FALSE;
	in->a = ra; in->b = ra; *rp = in->r; *fp = fa;
	return TRUE;
      }
    }
    if ( !compile_expr(v, a, &ra, &fa, depth+1) || !compile_expr(v, b, &rb, &fb, depth+1) ||
	 !(in = vmc_emit(v, op)) )
      return FALSE;
    in->a = ra; in->b = rb; *rp = in->r;
    *fp = op == I_ATAN2 ? TRUE : (fa || fb);
    return TRUE;
  }
  if ( arity == 1 )
  { term_t a = PL_new_term_ref();
    int op, ra, fa;
    insn *in;
    if ( !op_code(name, FALSE, &op) ) return FALSE;
    _PL_get_arg(1, t, a);
    if ( !compile_expr(v, a, &ra, &fa, depth+1) || !(in = vmc_emit(v, op)) ) return FALSE;
    in->a = ra; *rp = in->r;
    *fp = (op == I_NEG || op == I_ABS) ? fa : TRUE;
    return TRUE;
  }
  return FALSE;
}

/* plain_ref(t, &c): t is '$c'(C, V, V), a plain read of column C */
static int
plain_ref(term_t t, column **cp)
{ term_t a, p, x;
  void *data; PL_blob_t *type;
  if ( !PL_is_functor(t, FUNCTOR_cref3) ) return FALSE;
  a = PL_new_term_ref(); p = PL_new_term_ref(); x = PL_new_term_ref();
  _PL_get_arg(1, t, a); _PL_get_arg(2, t, p); _PL_get_arg(3, t, x);
  if ( !PL_get_blob(a, &data, NULL, &type) || type != &column_blob ) return FALSE;
  if ( !PL_is_variable(x) || PL_compare(p, x) != 0 ) return FALSE;
  *cp = data;
  return TRUE;
}

static int has_ref(term_t t, int depth);
static foreign_t col_select_eq(term_t ps, term_t tc, term_t v, term_t teq, term_t out);

/* col_test(+Ps, +Goal, -Out) is semidet: Out the particles of Ps in which
   Goal holds: a comparison of expressions over columns (at least one
   column), or V == Value or V \== Value with V a plain read of a column
   and Value ground; fails where it cannot (the caller's Prolog loop runs) */
static foreign_t
col_test(term_t ps, term_t goal, term_t out)
{ atom_t name;
  size_t arity;
  term_t a, b;
  int op;
  if ( !PL_get_name_arity(goal, &name, &arity) || arity != 2 ) return FALSE;
  a = PL_new_term_ref(); b = PL_new_term_ref();
  _PL_get_arg(1, goal, a); _PL_get_arg(2, goal, b);
  { const char *sn = PL_atom_chars(name);
    int eq = !strcmp(sn, "==") ? 1 : !strcmp(sn, "\\==") ? 0 : -1;
    if ( eq >= 0 )
    { column *c;
      term_t v;
      if ( plain_ref(a, &c) ) v = b;
      else if ( plain_ref(b, &c) ) v = a;
      else return FALSE;
      if ( !PL_is_ground(v) || has_ref(v, 0) ) return FALSE;
      { term_t teq = PL_new_term_ref(), tc = PL_new_term_ref();
	if ( !PL_put_bool(teq, eq) ) return FALSE;
	_PL_get_arg(1, v == b ? a : b, tc);
	return col_select_eq(ps, tc, v, teq, out);
      }
    }
  }
  if ( !cmp_code(name, &op) ) return FALSE;
  { vmc *v = malloc(sizeof(vmc));
    int ra, rb, fa, fb, rc;
    if ( !v ) return FALSE;
    vmc_init(v);
    rc = compile_expr(v, a, &ra, &fa, 0) && compile_expr(v, b, &rb, &fb, 0) &&
	 run_test(&v->m, op, ra, rb, ps, out);
    free(v);
    return rc;
  }
}

/* col_instance(+Ps, +Tmpl, !C) is semidet: each particle of Ps not drawn
   yet in C gets its instance of Tmpl: a plain read of a column (the
   particle's value copied), or a tuple of expressions (or one expression)
   whose values are floats in every particle (a column's number, a float,
   arithmetic with a float in it: as the Prolog loop would make them); a
   template's components are instantiated, not evaluated, so each is a
   float, a column reference or a deferred expression.  Fails where it
   cannot (the caller's Prolog loop runs). */
static foreign_t
col_instance(term_t ps, term_t tmpl, term_t tc)
{ column *c, *from;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( plain_ref(tmpl, &from) )
  { term_t tf = PL_new_term_ref();
    _PL_get_arg(1, tmpl, tf);
    return col_copy_each(ps, tf, tc);
  }
  { vmc *v = malloc(sizeof(vmc));
    int regs[MAX_K], k = 0, rc = FALSE;
    term_t r = PL_copy_term_ref(tmpl), e = PL_new_term_ref();
    if ( !v ) return FALSE;
    vmc_init(v);
    for(;;)
    { int last = !PL_is_functor(r, FUNCTOR_comma2), f;
      if ( last ) { if ( !PL_put_term(e, r) ) goto out; } else _PL_get_arg(1, r, e);
      if ( k >= MAX_K ) goto out;
      if ( !(PL_is_float(e) || PL_is_functor(e, FUNCTOR_cref3) ||
	     PL_is_functor(e, FUNCTOR_xref1)) ) goto out;
      if ( !compile_expr(v, e, &regs[k], &f, 0) || !f ) goto out;
      k++;
      if ( last ) break;
      _PL_get_arg(2, r, r);
    }
    rc = run_instance(&v->m, regs, k, ps, c);
  out:
    free(v);
    return rc;
  }
}

		 /*******************************
		 *          PARTITIONS          *
		 *******************************/

/* The key of particle i in the columns cs: a hash of its cells (FALSE for
   a term with variables, which the caller groups in Prolog). */
static int
cell_hash(column **cs, int nc, size_t i0, uint64_t *hp)
{ uint64_t h = 1469598103934665603ULL;
  for(int j=0; j<nc; j++)
  { column *c = cs[j];
    size_t i = CI(c, i0);
    uint64_t x;
    switch(c->tag[i])
    { case T_U: x = 1; break;
      case T_UNDEF: x = 2; break;
      case T_ATOM: x = (uint64_t)c->x[i]; break;
      case T_LIST:
      { alist *l = (alist*)c->x[i];
	x = 5;
	for(size_t q=0; q<l->n; q++)
	{ uint64_t y = (uint64_t)l->a[q].v;
	  if ( l->a[q].rec )		/* (equal terms, equal external records) */
	  { fid_t fid = PL_open_foreign_frame();
	    term_t t = PL_new_term_ref();
	    char *rec; size_t len;
	    if ( !PL_recorded((record_t)l->a[q].v, t) || !(rec = PL_record_external(t, &len)) )
	    { PL_discard_foreign_frame(fid);
	      return FALSE;
	    }
	    y = 7;
	    for(size_t b=0; b<len; b++) y = (y ^ (uint8_t)rec[b]) * 1099511628211ULL;
	    PL_erase_external(rec);
	    PL_discard_foreign_frame(fid);
	  }
	  x = (x ^ y) * 1099511628211ULL;
	}
	break;
      }
      case T_NUM:
	x = 3;
	for(int q=0; q<c->k; q++)
	{ uint64_t b; memcpy(&b, &c->f[i*(size_t)c->k+(size_t)q], sizeof(b));
	  x = (x ^ b) * 1099511628211ULL;
	}
	break;
      case T_TERM:
      { /* (equal terms, equal external records: a hash of its bytes) */
	fid_t fid = PL_open_foreign_frame();
	term_t t = PL_new_term_ref();
	char *rec; size_t len;
	x = 4;
	if ( !PL_recorded((record_t)c->x[i], t) || !PL_is_ground(t) ||
	     !(rec = PL_record_external(t, &len)) )
	{ PL_discard_foreign_frame(fid);
	  return FALSE;
	}
	for(size_t q=0; q<len; q++) x = (x ^ (uint8_t)rec[q]) * 1099511628211ULL;
	PL_erase_external(rec);
	PL_discard_foreign_frame(fid);
	break;
      }
      default:
	return FALSE;
    }
    h = (h ^ x) * 1099511628211ULL;
    h ^= h >> 29;
  }
  *hp = h;
  return TRUE;
}


/* classes(c): each cell's class (c->cls), computed once after the last
   write: equal values, equal classes; FALSE if a value is not ground */
static int
classes(column *c)
{ size_t cap, ncls = 0;
  size_t *slot;
  if ( c->cls_valid ) return TRUE;
  if ( c->uni )				/* (one class, of the one value) */
  { uint64_t h;
    column *one = c;
    if ( c->n > 0 && !cell_hash(&one, 1, 0, &h) ) return FALSE;
    c->cls_valid = 1;
    return TRUE;
  }
  if ( !c->cls )
  { if ( !(c->cls = malloc((c->n ? c->n : 1)*sizeof(uint32_t))) ) return FALSE;
    count_bytes(c->n*sizeof(uint32_t));
  }
  for(cap=16; cap < 2*c->n; cap *= 2) ;
  if ( !(slot = calloc(cap, sizeof(size_t))) ) return FALSE;   /* representative + 1 */
  for(size_t i=0; i<c->n; i++)
  { uint64_t h;
    size_t s;
    column *one = c;
    if ( !cell_hash(&one, 1, i, &h) ) { free(slot); return FALSE; }
    for(s = (size_t)h & (cap-1); ; s = (s+1) & (cap-1))
    { if ( slot[s] == 0 )
      { slot[s] = i+1;
	c->cls[i] = (uint32_t)ncls++;
	break;
      }
      if ( same_cell(c, slot[s]-1, c, i) )
      { c->cls[i] = c->cls[slot[s]-1];
	break;
      }
    }
  }
  free(slot);
  c->cls_valid = 1;
  return TRUE;
}

#define CLS(c, i) ((c)->uni ? (uint32_t)0 : (c)->cls[i])

static int
class_hash(column **cs, int nc, size_t i, uint64_t *hp)
{ uint64_t h = 1469598103934665603ULL;
  for(int j=0; j<nc; j++)
  { h = (h ^ CLS(cs[j], i)) * 1099511628211ULL;
    h ^= h >> 29;
  }
  *hp = h;
  return TRUE;
}

static int
same_class(column **cs, int nc, size_t i, size_t j)
{ for(int q=0; q<nc; q++)
    if ( CLS(cs[q], i) != CLS(cs[q], j) ) return FALSE;
  return TRUE;
}

/* col_partition(+Ps, +Cols, -Groups) is semidet: Groups, a list of Vs-Ps, the
   particles of Ps grouped by their values Vs in the columns Cols (a group
   per distinct list of values, in the order of their first particle, its
   particles in the order of Ps); fails if a value is not ground */
static foreign_t
col_partition(term_t ps, term_t tcols, term_t out)
{ column *cs[MAX_COLS];
  int nc = 0;
  size_t np, ng = 0, cap;
  const uint32_t *idx;
  pview pv;
  size_t *slot_rep = NULL, *group_of = NULL, *rep = NULL, *count = NULL, *next = NULL;
  size_t *head = NULL, *tail = NULL;
  int rc = FALSE;

  { term_t l = PL_copy_term_ref(tcols), h = PL_new_term_ref();
    while( PL_get_list(l, h, l) )
    { void *data; PL_blob_t *type;
      if ( nc >= MAX_COLS || !PL_get_blob(h, &data, NULL, &type) || type != &column_blob )
	return FALSE;
      cs[nc++] = data;
    }
  }
  if ( nc == 0 ) return FALSE;
  for(int q=0; q<nc; q++) if ( !classes(cs[q]) ) return FALSE;
  if ( !get_batch(ps, cs[0], &pv) ) return FALSE;
  idx = pv.v; np = pv.n;
  for(int q=1; q<nc; q++) if ( cs[q]->n != cs[0]->n ) { free_view(&pv); return FALSE; }
  for(cap=16; cap < 2*np; cap *= 2) ;
  slot_rep = malloc(cap*sizeof(size_t));	/* group number + 1, 0 free */
  group_of = malloc((np?np:1)*sizeof(size_t));
  rep = malloc((np?np:1)*sizeof(size_t));
  next = malloc((np?np:1)*sizeof(size_t));
  head = malloc((np?np:1)*sizeof(size_t));
  tail = malloc((np?np:1)*sizeof(size_t));
  count = malloc((np?np:1)*sizeof(size_t));
  if ( !slot_rep || !group_of || !rep || !next || !head || !tail || !count ) goto out;
  memset(slot_rep, 0, cap*sizeof(size_t));
  for(size_t j=0; j<np; j++)
  { uint64_t hsh;
    size_t s;
    if ( !class_hash(cs, nc, idx[j], &hsh) ) goto out;
    for(s = (size_t)hsh & (cap-1); ; s = (s+1) & (cap-1))
    { if ( slot_rep[s] == 0 )
      { slot_rep[s] = ++ng;
	rep[ng-1] = idx[j]; head[ng-1] = j; tail[ng-1] = j; count[ng-1] = 0;
	break;
      }
      if ( same_class(cs, nc, rep[slot_rep[s]-1], idx[j]) )
      { next[tail[slot_rep[s]-1]] = j; tail[slot_rep[s]-1] = j;
	break;
      }
    }
    group_of[j] = slot_rep[s]-1;
    next[j] = (size_t)-1;
    count[slot_rep[s]-1]++;
  }
  { term_t gl = PL_copy_term_ref(out), gh = PL_new_term_ref();
    term_t vs = PL_new_term_ref(), v = PL_new_term_ref(), pl = PL_new_term_ref();
    term_t pair = PL_new_term_ref();
    for(size_t g=0; g<ng; g++)
    { PL_put_nil(vs);
      for(int q=nc-1; q>=0; q--)
      { if ( !put_cell(v, cs[q], rep[g]) || !PL_cons_list(vs, v, vs) ) goto out;
      }
      if ( ng == 1 )			/* (one group: the batch itself) */
      { if ( !PL_put_term(pl, ps) ) goto out;
      } else
      { uint32_t *mine = malloc(count[g]*sizeof(uint32_t));
	size_t m = 0;
	if ( !mine ) goto out;
	for(size_t j=head[g]; j != (size_t)-1; j = next[j]) mine[m++] = idx[j];
	PL_put_variable(pl);
	if ( !unify_batch(pl, mine, m, pv.blob) ) { free(mine); goto out; }
	free(mine);
      }
      if ( !PL_cons_functor(pair, FUNCTOR_minus2, vs, pl) ||
	   !PL_unify_list(gl, gh, gl) || !PL_unify(gh, pair) )
	goto out;
    }
    rc = PL_unify_nil(gl);
  }
out:
  free_view(&pv); free(slot_rep); free(group_of); free(rep); free(next); free(head); free(tail);
  free(count);
  return rc;
}

/* col_draw_uniform(+Ps, +ListC, !C, +Seed) is semidet: each particle of Ps
   not drawn yet in C gets an element of its list in ListC, uniformly (as
   uniform(L) draws: the element at floor(U * length), U in [0, 1));
   fails, writing nothing, if a value is not a non-empty list */
static foreign_t
col_draw_uniform(term_t ps, term_t tl, term_t tc, term_t ts)
{ column *lc, *c;
  size_t np;
  const uint32_t *idx;
  pview pv;
  rng r;
  fid_t fid;
  int rc = FALSE;
  if ( !get_column_raw(tl, &lc) || !get_column(tc, &c) || !get_seed(ts, &r) ) return FALSE;
  if ( lc->n != c->n ) return FALSE;
  if ( !get_batch(ps, c, &pv) ) return FALSE;
  idx = pv.v; np = pv.n;
  for(size_t j=0; j<np; j++)
    if ( c->tag[idx[j]] == T_U && lc->tag[CI(lc, idx[j])] != T_TERM && lc->tag[CI(lc, idx[j])] != T_LIST )
    { free_view(&pv); return FALSE; }
  { term_t l = PL_new_term_ref(), h = PL_new_term_ref();   /* (before the frame) */
    size_t len;
    fid = PL_open_foreign_frame();
    /* (first every list checked, then the draws: nothing written on failure) */
    for(size_t j=0; j<np; j++)
    { if ( c->tag[idx[j]] != T_U || lc->tag[CI(lc, idx[j])] == T_LIST ) continue;
      if ( !PL_recorded((record_t)lc->x[CI(lc, idx[j])], l) ||
	   PL_skip_list(l, 0, &len) != PL_LIST || len == 0 )
	goto out;
      PL_rewind_foreign_frame(fid);
    }
    for(size_t j=0; j<np; j++)
    { size_t i = idx[j], pick;
      if ( c->tag[i] != T_U ) continue;
      if ( lc->tag[CI(lc, i)] == T_LIST )
      { alist *al = (alist*)lc->x[CI(lc, i)];
	pick = (size_t)floor((rng_uniform(&r) - 0x1.0p-53) * (double)al->n);
	if ( pick >= al->n ) pick = al->n-1;
	if ( !put_item(l, &al->a[pick]) || !set_cell(c, i, l) ) goto out;
	PL_rewind_foreign_frame(fid);
	continue;
      }
      if ( !PL_recorded((record_t)lc->x[CI(lc, i)], l) ) goto out;
      if ( PL_skip_list(l, 0, &len) != PL_LIST || len == 0 ) goto out;
      pick = (size_t)floor((rng_uniform(&r) - 0x1.0p-53) * (double)len);
      if ( pick >= len ) pick = len-1;
      for(size_t q=0; q<=pick; q++)
      { if ( !PL_get_list(l, h, l) ) goto out;
      }
      if ( !set_cell(c, i, h) ) goto out;
      PL_rewind_foreign_frame(fid);
    }
    rc = TRUE;
  }
out:
  PL_close_foreign_frame(fid);
  free_view(&pv);
  return rc;
}

/* col_select_eq(+Ps, +C, +V, +Eq, -Out): Out the particles of Ps whose
   value in C is == V (Eq true) or \== V (Eq false) */
static foreign_t
col_select_eq(term_t ps, term_t tc, term_t v, term_t teq, term_t out)
{ column *c, *tmp;
  int eq;
  int rc = FALSE;
  pview p;
  char *keep;
  size_t m = 0;
  if ( !get_column_raw(tc, &c) || !PL_get_bool_ex(teq, &eq) ) return FALSE;
  if ( !get_batch(ps, c, &p) ) return FALSE;
  if ( !(tmp = new_column(1)) ) { free_view(&p); return PL_resource_error("memory"); }
  if ( !(keep = malloc(p.n ? p.n : 1)) )
  { free_cells(tmp); free_view(&p); return PL_resource_error("memory"); }
  if ( !set_cell(tmp, 0, v) ) goto out;
  for(size_t j=0; j<p.n; j++)
  { keep[j] = (char)(same_cell(c, p.v[j], tmp, 0) == eq);
    m += (size_t)keep[j];
  }
  rc = unify_selected(out, ps, &p, keep, m);
out:
  free(keep); free_cells(tmp); free_view(&p);
  return rc;
}

/* col_sources(+Indices, +Sizes, -Plans): for each group (of the sizes
   Sizes, in order), the sources of its particles (a blob: for each the
   group and the index in it of its ancestor), the 0-based indices into all
   groups' particles Indices */
static foreign_t
col_sources(term_t tis, term_t tsizes, term_t out)
{ size_t ng, total = 0, *size, *start;
  gplan **plan;
  int rc = FALSE;
  if ( !PL_skip_list(tsizes, 0, &ng) || ng == 0 ) return PL_type_error("list", tsizes);
  size = malloc(ng*sizeof(size_t)); start = malloc(ng*sizeof(size_t));
  plan = calloc(ng, sizeof(gplan*));
  if ( !size || !start || !plan ) { free(size); free(start); free(plan); return PL_resource_error("memory"); }
  { term_t l = PL_copy_term_ref(tsizes), h = PL_new_term_ref();
    for(size_t g=0; PL_get_list(l, h, l); g++)
    { int64_t n;
      if ( !PL_get_int64_ex(h, &n) || n < 0 ) goto out;
      size[g] = (size_t)n; start[g] = total; total += (size_t)n;
      if ( !(plan[g] = malloc(sizeof(gplan) + (n ? 2*(size_t)n : 1)*sizeof(uint32_t))) )
      { PL_resource_error("memory"); goto out; }
      plan[g]->n = (size_t)n;
    }
  }
  { term_t l = PL_copy_term_ref(tis), h = PL_new_term_ref();
    size_t len;
    if ( PL_skip_list(tis, 0, &len) != PL_LIST || len != total ) goto out;
    for(size_t g=0; g<ng; g++)
    { for(size_t j=0; j<size[g]; j++)
      { int64_t x;
	size_t q = 0;
	if ( !PL_get_list(l, h, l) || !PL_get_int64(h, &x) || x < 0 || (size_t)x >= total )
	  goto out;
	while( q+1 < ng && (size_t)x >= start[q+1] ) q++;
	plan[g]->gl[2*j] = (uint32_t)(q+1);
	plan[g]->gl[2*j+1] = (uint32_t)((size_t)x - start[q]);
      }
    }
  }
  { term_t gl = PL_copy_term_ref(out), gh = PL_new_term_ref();
    for(size_t g=0; g<ng; g++)
    { count_bytes(sizeof(gplan) + 2*plan[g]->n*sizeof(uint32_t));
      if ( !PL_unify_list(gl, gh, gl) || !PL_unify_blob(gh, plan[g], sizeof(gplan), &gplan_blob) )
	goto out;
      plan[g] = NULL;			/* (the blob's now) */
    }
    rc = PL_unify_nil(gl);
  }
out:
  for(size_t g=0; g<ng; g++) free(plan[g]);
  free(plan); free(size); free(start);
  return rc;
}

		 /*******************************
		 *     SETS OF PARTICLES        *
		 *******************************/

/* ord_subtract/3, ord_union/3, ord_union/2 and ord_intersection/3 on
   batches (each fails, for the caller's ordsets, on a list of anything
   else).  The result is one of the arguments where it can be (a batch
   minus one it does not meet is itself); else a blob if the first batch
   is one. */

/* in_view(p, x, &from): x is in p (binary search from index from on,
   which moves past x) */
static int
in_view(const pview *p, uint32_t x, size_t *from)
{ size_t lo = *from, hi = p->n;
  while( lo < hi )
  { size_t mid = lo + (hi-lo)/2;
    if ( p->v[mid] < x ) lo = mid+1; else hi = mid;
  }
  *from = lo;
  return lo < p->n && p->v[lo] == x;
}

/* ps_filter(a, b, out, want): the elements of a that are (want) or are
   not in b */
static foreign_t
ps_filter(term_t ta, term_t tb, term_t out, int want)
{ pview a, b;
  char *keep;
  size_t m = 0;
  int rc;
  if ( !get_view(ta, 0, &a) ) return FALSE;
  if ( !get_view(tb, 0, &b) ) { free_view(&a); return FALSE; }
  if ( !(keep = malloc(a.n ? a.n : 1)) )
  { free_view(&a); free_view(&b); return PL_resource_error("memory"); }
  if ( b.n*8 < a.n )			/* (a few elements in b: searched) */
  { size_t from = 0;
    memset(keep, !want, a.n);
    m = want ? 0 : a.n;
    for(size_t j=0; j<b.n; j++)
    { size_t at = from;
      if ( in_view(&a, b.v[j], &at) )
      { keep[at] = (char)want;
	m += want ? 1 : (size_t)-1;
      }
      from = at;
    }
  } else
  { size_t q = 0;
    for(size_t j=0; j<a.n; j++)
    { while( q < b.n && b.v[q] < a.v[j] ) q++;
      keep[j] = (char)((q < b.n && b.v[q] == a.v[j]) == want);
      m += (size_t)keep[j];
    }
  }
  rc = unify_selected(out, ta, &a, keep, m);
  free(keep); free_view(&a); free_view(&b);
  return rc;
}

static foreign_t
ps_subtract(term_t a, term_t b, term_t out)
{ return ps_filter(a, b, out, FALSE);
}

static foreign_t
ps_intersection(term_t a, term_t b, term_t out)
{ pview va, vb;				/* (the smaller one filtered: the same set) */
  int swap;
  if ( !get_view(a, 0, &va) ) return FALSE;
  if ( !get_view(b, 0, &vb) ) { free_view(&va); return FALSE; }
  swap = vb.n < va.n && vb.blob == va.blob;
  free_view(&va); free_view(&vb);
  return swap ? ps_filter(b, a, out, TRUE) : ps_filter(a, b, out, TRUE);
}

/* ps_union(+Lists, -Union) */
static foreign_t
ps_union_list(term_t ls, term_t out)
{ term_t l = PL_copy_term_ref(ls), h = PL_new_term_ref();
  size_t cap = 1024, max = 0, total = 0, nonempty = 0;
  uint8_t *mark = calloc(cap, 1);
  int blob = FALSE, rc;
  term_t one = PL_new_term_ref();
  if ( !mark ) return PL_resource_error("memory");
  while( PL_get_list(l, h, l) )
  { pview a;
    if ( !get_view(h, 0, &a) ) { free(mark); return FALSE; }
    if ( a.blob ) blob = TRUE;
    if ( a.n == 0 ) { free_view(&a); continue; }
    nonempty++;
    if ( !PL_put_term(one, h) ) { free(mark); return FALSE; }
    if ( (size_t)a.v[a.n-1]+1 > cap )
    { size_t ncap = cap;
      uint8_t *m2;
      while( ncap < (size_t)a.v[a.n-1]+1 ) ncap *= 2;
      if ( !(m2 = realloc(mark, ncap)) ) { free_view(&a); free(mark); return PL_resource_error("memory"); }
      memset(m2+cap, 0, ncap-cap);
      mark = m2; cap = ncap;
    }
    for(size_t j=0; j<a.n; j++) mark[a.v[j]] = 1;
    if ( (size_t)a.v[a.n-1]+1 > max ) max = (size_t)a.v[a.n-1]+1;
    total += a.n;
    free_view(&a);
  }
  if ( nonempty == 1 ) { free(mark); return PL_unify(out, one); }
  { uint32_t *v = malloc((total ? total : 1)*sizeof(uint32_t));
    size_t m = 0;
    if ( !v ) { free(mark); return PL_resource_error("memory"); }
    for(size_t i=0; i<max; i++) if ( mark[i] ) v[m++] = (uint32_t)i;
    free(mark);
    rc = unify_batch(out, v, m, blob);
    free(v);
    return rc;
  }
}

/* ps_union(+A, +B, -Union) */
static foreign_t
ps_union(term_t a, term_t b, term_t out)
{ term_t ls = PL_new_term_ref(), nil = PL_new_term_ref();
  PL_put_nil(nil);
  return PL_cons_list(ls, b, nil) && PL_cons_list(ls, a, ls) && ps_union_list(ls, out);
}

/* col_vm_finite(+Ps, +Cols, +Code, +ProbRegs, +Values, !C, +Seed) is
   semidet: each particle of Ps not drawn yet in C gets a draw of
   finite([P1:V1, ..., Pk:Vk]), Pi the registers ProbRegs after Code, Vi
   the cells of the column Values (as ddc_dist.pl draws it: U uniform in
   [0, 1), the first Vi whose cumulative probability exceeds U, else the
   last of positive probability); fails, writing nothing, if the loop is
   abandoned or a particle's probabilities are not a distribution (the
   caller's Prolog loop raises the error) */
static int
run_finite(const vm *m, const int *regs, int k, column *vals, term_t ps, column *c, rng *g)
{ double r[MAX_REGS];
  size_t np, *pick;
  const uint32_t *idx;
  pview pv;

  if ( k == 0 || (size_t)k != vals->n ) return FALSE;
  for(int j=0; j<m->ncol; j++)
    if ( m->col[j]->n != c->n ) return FALSE;
  if ( !get_batch(ps, c, &pv) ) return FALSE;
  idx = pv.v; np = pv.n;
  if ( !(pick = malloc((np ? np : 1)*sizeof(size_t))) ) { free_view(&pv); return FALSE; }
  for(size_t j=0; j<np; j++)
  { double sum = 0.0, u;
    int q, last = -1;
    pick[j] = (size_t)-1;
    if ( c->tag[idx[j]] != T_U ) continue;
    { int rc = vm_run(m, idx[j], r);
      if ( rc == VM_ABANDON ) goto abandon;
      if ( rc == VM_SKIP ) continue;
    }
    for(q=0; q<k; q++)
    { double p = r[regs[q]];
      if ( !(p >= 0.0) ) goto abandon;
      if ( p > 0.0 ) last = q;
      sum += p;
    }
    if ( fabs(sum - 1.0) > 1.0e-9 || last < 0 ) goto abandon;
    u = rng_uniform(g) - 0x1.0p-53;		/* [0, 1) */
    for(q=0; q<k; q++)
    { double p = r[regs[q]];
      if ( u < p ) break;
      if ( q == k-1 ) { q = last; break; }
      u -= p;
    }
    pick[j] = (size_t)q;
  }
  for(size_t j=0; j<np; j++)
  { if ( c->tag[idx[j]] != T_U || pick[j] == (size_t)-1 ) continue;
    if ( !copy_cell(c, idx[j], vals, pick[j]) ) { free(pick); free_view(&pv); return FALSE; }
  }
  free(pick); free_view(&pv);
  return TRUE;
abandon:
  free(pick); free_view(&pv);
  return FALSE;
}

static foreign_t
col_vm_finite(term_t ps, term_t cols, term_t code, term_t tregs, term_t tvals, term_t tc,
	      term_t ts)
{ vm m;
  column *c, *vals;
  int regs[MAX_REGS], k = 0, rc;
  rng g;

  if ( !get_column(tc, &c) || !get_column(tvals, &vals) || !get_seed(ts, &g) ) return FALSE;
  { term_t l = PL_copy_term_ref(tregs), h = PL_new_term_ref();
    while( PL_get_list(l, h, l) )
    { if ( k >= MAX_REGS || !PL_get_integer(h, &regs[k]) || !reg_ok(regs[k]) ) return FALSE;
      k++;
    }
  }
  if ( k == 0 || (size_t)k != vals->n ) return FALSE;
  if ( !vm_load(cols, code, &m) ) return FALSE;
  rc = run_finite(&m, regs, k, vals, ps, c, &g);
  free(m.code);
  return rc;
}

/* col_append_each(+Ps, !LC, +V) is semidet: each particle of Ps gets V
   appended to its list in LC; fails, writing nothing, if a value is not a
   list */
static foreign_t
col_append_each(term_t ps, term_t tc, term_t v)
{ column *c;
  size_t np;
  const uint32_t *idx;
  pview pv;
  int rc = FALSE;
  fid_t fid;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( !get_batch(ps, c, &pv) ) return FALSE;
  idx = pv.v; np = pv.n;
  { if ( PL_is_ground(v) )		/* (a ground term: lists of items, in place) */
    { int fast = TRUE, whole = c->uni && np == c->n;
      item it;
      for(size_t j=0; j<np && fast; j++)
      { size_t i = CI(c, idx[j]);
	uint8_t t = c->tag[i];
	fast = t == T_LIST || (t == T_ATOM && (atom_t)c->x[i] == ATOM_nil);
      }
      if ( fast && whole )		/* (every particle's list: the one list) */
      { static const uint32_t zero = 0;
	idx = &zero; np = 1;
      } else if ( fast && !expand(c) )
      { free_view(&pv); return FALSE; }
      if ( fast )
      { if ( !make_item(v, &it) ) { free_view(&pv); return FALSE; }
	for(size_t j=0; j<np; j++)
	{ size_t i = idx[j];
	  if ( c->tag[i] == T_ATOM )
	  { alist *l = new_alist(4);
	    if ( !l ) { free_item(&it); free_view(&pv); return FALSE; }
	    clear_cell(c, i);
	    c->x[i] = (uintptr_t)l;
	    SET_TAG(c, i, T_LIST);
	  }
	  { alist *l = (alist*)c->x[i];
	    if ( !alist_push(&l, &it) ) { free_item(&it); free_view(&pv); return FALSE; }
	    c->x[i] = (uintptr_t)l;
	    c->cls_valid = 0;
	  }
	}
	if ( whole )
	{ memset(c->cnt, 0, sizeof(c->cnt));
	  c->cnt[T_LIST] = c->n;
	}
	free_item(&it);
	free_view(&pv);
	return TRUE;
      }
    }
  }
  { term_t l = PL_new_term_ref();	/* (before the frame: a rewind keeps it) */
    size_t len;
    fid = PL_open_foreign_frame();
    for(size_t j=0; j<np; j++)
    { if ( !put_cell(l, c, idx[j]) || PL_skip_list(l, 0, &len) != PL_LIST ) goto out;
      PL_rewind_foreign_frame(fid);
    }
    for(size_t j=0; j<np; j++)
    { term_t elems, nl;
      if ( !put_cell(l, c, idx[j]) || PL_skip_list(l, 0, &len) != PL_LIST ) goto out;
      if ( !(elems = PL_new_term_refs((int)len+1)) ) goto out;
      nl = PL_new_term_ref();
      for(size_t q=0; q<len; q++)
      { if ( !PL_get_list(l, elems+q, l) ) goto out;
      }
      PL_put_nil(nl);
      if ( !PL_cons_list(nl, v, nl) ) goto out;
      for(size_t q=len; q-- > 0; )
      { if ( !PL_cons_list(nl, elems+q, nl) ) goto out;
      }
      if ( !set_cell(c, idx[j], nl) ) goto out;
      PL_rewind_foreign_frame(fid);
    }
    rc = TRUE;
  }
out:
  PL_close_foreign_frame(fid);
  free_view(&pv);
  return rc;
}

/* col_select_unify(+Ps, +C, +P, -Out): Out the particles of Ps whose value
   in C unifies with P, or is a number =:= P (as
   ddc_batch_columns:with_value/4 tests them) */
static foreign_t
col_select_unify(term_t ps, term_t tc, term_t p, term_t out)
{ column *c, *tmp;
  int rc = FALSE, pnum;
  double pv = 0.0;
  pview b;
  char *keep;
  size_t m = 0;
  if ( !get_column_raw(tc, &c) ) return FALSE;
  if ( !get_batch(ps, c, &b) ) return FALSE;
  if ( !(tmp = new_column(1)) ) { free_view(&b); return PL_resource_error("memory"); }
  if ( !(keep = malloc(b.n ? b.n : 1)) )
  { free_cells(tmp); free_view(&b); return PL_resource_error("memory"); }
  if ( !set_cell(tmp, 0, p) ) goto out;
  pnum = PL_is_number(p) && PL_get_float(p, &pv);
  { term_t v = PL_new_term_ref();
    for(size_t j=0; j<b.n; j++)
    { size_t i = b.v[j];
      int ok;
      if ( c->tag[CI(c, i)] == T_TERM )
      { fid_t f2 = PL_open_foreign_frame();
	double x;
	ok = put_cell(v, c, i) && PL_unify(v, p);
	PL_discard_foreign_frame(f2);	/* (the bindings undone) */
	if ( !ok && pnum )
	{ f2 = PL_open_foreign_frame();
	  ok = put_cell(v, c, i) && PL_is_number(v) && PL_get_float(v, &x) && x == pv;
	  PL_discard_foreign_frame(f2);
	}
      } else if ( same_cell(c, i, tmp, 0) )
	ok = TRUE;
      else
	ok = pnum && c->tag[CI(c, i)] == T_NUM && c->k == 1 && c->f[CI(c, i)] == pv;
      keep[j] = (char)ok;
      m += (size_t)ok;
    }
  }
  rc = unify_selected(out, ps, &b, keep, m);
out:
  free(keep); free_cells(tmp); free_view(&b);
  return rc;
}

/* col_with_arity(+Ps, +C, +K, -Out): Out the particles of Ps whose value in
   C is a tuple of K or more elements (subsumed by (_, ..., _) of K) */
static foreign_t
col_with_arity(term_t ps, term_t tc, term_t tk, term_t out)
{ column *c;
  int k, rc;
  pview b;
  char *keep;
  size_t m = 0;
  if ( !get_column_raw(tc, &c) || !PL_get_integer_ex(tk, &k) ) return FALSE;
  if ( !get_batch(ps, c, &b) ) return FALSE;
  if ( c->k >= k && c->cnt[T_NUM] == c->n )
  { free_view(&b);
    return PL_unify(out, ps);
  }
  if ( !(keep = malloc(b.n ? b.n : 1)) ) { free_view(&b); return PL_resource_error("memory"); }
  { term_t v = PL_new_term_ref();
    for(size_t j=0; j<b.n; j++)
    { size_t i = b.v[j];
      int ok;
      switch(c->tag[CI(c, i)])
      { case T_NUM: ok = c->k >= k; break;
	case T_TERM:
	{ fid_t f = PL_open_foreign_frame();
	  int q = 1;
	  ok = put_cell(v, c, i);
	  while( ok && q < k && PL_is_functor(v, FUNCTOR_comma2) )
	  { _PL_get_arg(2, v, v); q++; }
	  ok = ok && q == k;
	  PL_discard_foreign_frame(f);
	  break;
	}
	default: ok = FALSE;
      }
      keep[j] = (char)ok;
      m += (size_t)ok;
    }
  }
  rc = unify_selected(out, ps, &b, keep, m);
  free(keep); free_view(&b);
  return rc;
}

/* col_sets_each(+Ps, +LC, !C): each particle of Ps gets in C its list in LC
   without repeats (the first of each, as list_to_set/2) */
static foreign_t
col_sets_each(term_t ps, term_t tl, term_t tc)
{ column *lc, *c;
  size_t np;
  const uint32_t *idx;
  pview pv;
  int rc = FALSE, whole;
  static const uint32_t zero = 0;
  if ( !get_column_raw(tl, &lc) || !get_column_raw(tc, &c) ) return FALSE;
  if ( lc->n != c->n ) return FALSE;
  if ( !get_batch(ps, c, &pv) ) return FALSE;
  idx = pv.v; np = pv.n;
  whole = c->uni && c->tag[0] == T_U && lc->uni && np == c->n;
  if ( whole ) { idx = &zero; np = 1; }	/* (one list for every particle: one set) */
  else if ( !expand(c) ) { free_view(&pv); return FALSE; }
  { term_t l = PL_new_term_ref(), nl = PL_new_term_ref();
    fid_t fid = PL_open_foreign_frame();
    for(size_t j=0; j<np; j++)
    { size_t i = idx[j], len, m = 0;
      term_t el;
      int dup = FALSE;
      if ( !put_cell(l, lc, i) || PL_skip_list(l, 0, &len) != PL_LIST ) goto out;
      if ( len < 2 )
      { if ( whole ? !set_uniform(c, l) : !copy_cell(c, i, lc, i) ) goto out;
	PL_rewind_foreign_frame(fid);
	continue;
      }
      if ( !(el = PL_new_term_refs((int)len)) ) goto out;
      for(size_t q=0; q<len; q++)
      { term_t x = PL_new_term_ref();
	int seen = FALSE;
	if ( !PL_get_list(l, x, l) ) goto out;
	for(size_t r=0; r<m && !seen; r++)
	  if ( PL_compare(el+r, x) == 0 ) seen = TRUE;
	if ( seen ) dup = TRUE;
	else if ( !PL_put_term(el+m++, x) ) goto out;
      }
      if ( !dup )
      { if ( whole ? !(put_cell(nl, lc, 0) && set_uniform(c, nl)) : !copy_cell(c, i, lc, i) )
	  goto out;
      } else
      { PL_put_nil(nl);
	for(size_t q=m; q-- > 0; )
	  if ( !PL_cons_list(nl, el+q, nl) ) goto out;
	if ( whole ? !set_uniform(c, nl) : !set_cell(c, i, nl) ) goto out;
      }
      PL_rewind_foreign_frame(fid);
    }
    rc = TRUE;
  out:
    PL_close_foreign_frame(fid);
  }
  free_view(&pv);
  return rc;
}

/* col_gc_due(+Limit) is semidet: more than Limit bytes of columns were
   allocated since it last succeeded (then the count starts again) */
static foreign_t
col_gc_due(term_t tl)
{ int64_t limit;
  size_t n;
  if ( !PL_get_int64_ex(tl, &limit) ) return FALSE;
  n = __atomic_load_n(&col_bytes, __ATOMIC_RELAXED);
  if ( (int64_t)n <= limit ) return FALSE;
  __atomic_store_n(&col_bytes, 0, __ATOMIC_RELAXED);
  return TRUE;
}

/* col_has_ref(@T) is semidet: T holds a column reference '$c'(C, P, V) or a
   deferred expression '$x'(E) (ddc_batch_columns:has_column/1, walked in
   C: it is asked of every goal and distribution of a batch) */
static int
has_ref(term_t t, int depth)
{ if ( !PL_is_compound(t) ) return FALSE;
  if ( PL_is_functor(t, FUNCTOR_cref3) || PL_is_functor(t, FUNCTOR_xref1) ) return TRUE;
  if ( depth > 10000 ) return -1;
  { size_t arity;
    atom_t name;
    term_t a = PL_new_term_ref();
    int rc = FALSE;
    if ( !PL_get_name_arity(t, &name, &arity) ) return FALSE;
    for(size_t i=1; i<=arity && !rc; i++)
    { _PL_get_arg(i, t, a);
      rc = has_ref(a, depth+1);
    }
    PL_reset_term_refs(a);
    return rc;
  }
}

static foreign_t
col_has_ref(term_t t)
{ int rc = has_ref(t, 0);
  if ( rc < 0 ) return PL_resource_error("c_stack");
  return rc;
}

/* col_version(-V): the version of this library's interface */
static foreign_t
col_version(term_t v)
{ return PL_unify_integer(v, DDC_COLUMNS_VERSION);
}

install_t
install_ddc_columns(void)
{ zig_init();
 ATOM_u       = PL_new_atom("$u");
  ATOM_undef   = PL_new_atom("$undef");
  ATOM_open    = PL_new_atom("open");
  ATOM_defined = PL_new_atom("defined");
  ATOM_mixed   = PL_new_atom("mixed");
  ATOM_done    = PL_new_atom("done");
  ATOM_none    = PL_new_atom("$none");
  FUNCTOR_comma2 = PL_new_functor(PL_new_atom(","), 2);
  FUNCTOR_same1  = PL_new_functor(PL_new_atom("same"), 1);
  FUNCTOR_minus2 = PL_new_functor(PL_new_atom("-"), 2);
  FUNCTOR_cref3  = PL_new_functor(PL_new_atom("$c"), 3);
  FUNCTOR_xref1  = PL_new_functor(PL_new_atom("$x"), 1);

  PL_register_foreign("col_version",     1, col_version,     0);
  PL_register_foreign("col_gc_due",      1, col_gc_due,      0);
  PL_register_foreign("col_has_ref",     1, col_has_ref,     0);
  PL_register_foreign("col_new",         3, col_new,         0);
  PL_register_foreign("col_arg",         3, col_arg,         0);
  PL_register_foreign("col_setarg",      3, col_setarg,      0);
  PL_register_foreign("col_is_u",        2, col_is_u,        0);
  PL_register_foreign("col_size",        2, col_size,        0);
  PL_register_foreign("col_is",          1, col_is,          0);
  PL_register_foreign("col_list",        2, col_list,        0);
  PL_register_foreign("col_from_list",   2, col_from_list,   0);
  PL_register_foreign("col_uncomputed",  3, col_uncomputed,  0);
  PL_register_foreign("col_defined_at",  3, col_defined_at,  0);
  PL_register_foreign("col_set_each",    3, col_set_each,    0);
  PL_register_foreign("col_status",      2, col_status,      0);
  PL_register_foreign("col_rows",        4, col_rows,        0);
  PL_register_foreign("col_pack_rows",   3, col_pack_rows,   0);
  PL_register_foreign("col_floats_into", 4, col_floats_into, 0);
  PL_register_foreign("col_floats_list", 2, col_floats_list, 0);
  PL_register_foreign("col_weights_update", 6, col_weights_update, 0);
  PL_register_foreign("col_systematic_indices", 3, col_systematic_indices, 0);
  PL_register_foreign("col_row_width",   2, col_row_width,   0);
  PL_register_foreign("col_all_same",    3, col_all_same,    0);
  PL_register_foreign("col_num_arity",   2, col_num_arity,   0);
  PL_register_foreign("col_gather",      3, col_gather,      0);
  PL_register_foreign("col_plan_size",   2, col_plan_size,   0);
  PL_register_foreign("col_draw_gauss",  5, col_draw_gauss,  0);
  PL_register_foreign("col_weigh_gauss", 7, col_weigh_gauss, 0);
  PL_register_foreign("col_vm_test",     7, col_vm_test,     0);
  PL_register_foreign("col_vm_instance", 5, col_vm_instance, 0);
  PL_register_foreign("col_copy_each",   3, col_copy_each,   0);
  PL_register_foreign("col_test",        3, col_test,        0);
  PL_register_foreign("col_instance",    3, col_instance,    0);
  PL_register_foreign("col_partition",       3, col_partition,       0);
  PL_register_foreign("col_draw_uniform",4, col_draw_uniform,0);
  PL_register_foreign("col_select_eq",   5, col_select_eq,   0);
  PL_register_foreign("col_sources",     3, col_sources,     0);
  PL_register_foreign("col_vm_finite",   7, col_vm_finite,   0);
  PL_register_foreign("col_append_each", 3, col_append_each, 0);
  PL_register_foreign("col_select_unify",4, col_select_unify,0);
  PL_register_foreign("col_with_arity",  4, col_with_arity,  0);
  PL_register_foreign("col_sets_each",   3, col_sets_each,   0);
  PL_register_foreign("ps_all",          2, ps_all,          0);
  PL_register_foreign("ps_list",         2, ps_list,         0);
  PL_register_foreign("ps_blob",         2, ps_blob,         0);
  PL_register_foreign("ps_size",         2, ps_size,         0);
  PL_register_foreign("ps_first",        2, ps_first,        0);
  PL_register_foreign("$ps_subtract",     3, ps_subtract,     0);
  PL_register_foreign("$ps_intersection", 3, ps_intersection, 0);
  PL_register_foreign("$ps_union",        3, ps_union,        0);
  PL_register_foreign("$ps_union",        2, ps_union_list,   0);
}
