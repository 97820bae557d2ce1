#!/bin/bash
# Run from the repository root; prints "0 differ" when the two README commands share one build.
# Packages both README commands compile whose features differ between them (each is compiled twice).
cargo tree -p loomkin-cli -e normal,build -f "{p} [{f}]" --prefix none 2>/dev/null | sed 's/ (\*)//;s/ (proc-macro)//' | sort -u > /tmp/vocab-run.txt
cargo tree --workspace -e normal,build,dev -f "{p} [{f}]" --prefix none 2>/dev/null | sed 's/ (\*)//;s/ (proc-macro)//' | sort -u > /tmp/vocab-test.txt
python3 - <<'P'
import re
def load(p):
    d={}
    for l in open(p):
        m=re.match(r'(\S+) (v\S+)(?: \([^)]*\))? \[(.*)\]$',l.strip())
        if m: d.setdefault((m.group(1),m.group(2)),set()).add(m.group(3))
    return d
r=load('/tmp/vocab-run.txt'); t=load('/tmp/vocab-test.txt')
n=0
for k in sorted(r):
    if k in t and r[k]!=t[k]:
        n+=1; print(k[0],k[1],'run',r[k],'test',t[k])
print(n,'differ;',len([k for k in r if k in t]),'shared')
P
