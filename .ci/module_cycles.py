# The module import graph of src/ (non-test code, the float reference aside)
# and its cycles: CI fails on any (issue #42, item 2). `-v` prints the graph.
import re,os,sys
root='src'
mods={}
for d,_,fs in os.walk(root):
    for f in fs:
        if not f.endswith('.rs'): continue
        p=os.path.join(d,f); rel=os.path.relpath(p,root)[:-3]
        parts=rel.split('/')
        if parts[-1] in ('mod','lib'): parts=parts[:-1]
        if 'reference' in parts: continue
        mods['::'.join(parts)]=p
def resolve(cur,path):
    segs=path.split('::')
    if segs[0]=='crate': base=[]; segs=segs[1:]
    elif segs[0]=='super':
        base=cur.split('::')[:-1] if cur else []
        segs=segs[1:]
        while segs and segs[0]=='super': base=base[:-1]; segs=segs[1:]
    elif segs[0]=='self': base=cur.split('::') if cur else []; segs=segs[1:]
    else: return None
    full=base+segs
    for n in range(len(full),0,-1):
        m='::'.join(full[:n])
        if m in mods: return m
    return None
g={m:set() for m in mods}
for m,p in mods.items():
    src=open(p).read()
    i=src.find('#[cfg(test)]\nmod tests')
    if i>=0: src=src[:i]
    src=re.sub(r'//[^\n]*','',src)
    for path in re.findall(r'\b((?:crate|super|self)(?:::\w+)+)',src):
        t=resolve(m,path)
        if t and t!=m and not m.startswith(t+'::') and not t.startswith(m+'::') or (t and t!=m and m=='' ):
            g[m].add(t)
    for path,inner in re.findall(r'\b((?:crate|super|self)(?:::\w+)*)::\{([^}]*)\}',src):
        for it in inner.split(','):
            it=it.strip().split(' as ')[0]
            if not it or it=='self': continue
            t=resolve(m,path+'::'+it)
            if t and t!=m and not m.startswith(t+'::') and not t.startswith(m+'::'): g[m].add(t)
# Tarjan
idx={};low={};st=[];on=set();sccs=[];c=[0]
sys.setrecursionlimit(10000)
def sc(v):
    idx[v]=low[v]=c[0];c[0]+=1;st.append(v);on.add(v)
    for w in g[v]:
        if w not in idx: sc(w);low[v]=min(low[v],low[w])
        elif w in on: low[v]=min(low[v],idx[w])
    if low[v]==idx[v]:
        comp=[]
        while True:
            w=st.pop();on.discard(w);comp.append(w)
            if w==v: break
        if len(comp)>1: sccs.append(comp)
for v in g:
    if v not in idx: sc(v)
if '-v' in sys.argv:
    for m in sorted(g): print(m or 'lib','->',', '.join(sorted(x or 'lib' for x in g[m])))
print('cycles:',sccs if sccs else 'none')
sys.exit(1 if sccs else 0)
