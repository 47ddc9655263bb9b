#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Midpoint subdivision of a triangle OFF mesh (each triangle into four),
for large test meshes made at run time: subdivide.py IN.off LEVELS OUT.off"""
import sys, numpy as np
def read_off(p):
    t=open(p).read().split()
    assert t[0]=='OFF'; nv,nf=int(t[1]),int(t[2]); i=4
    V=np.array(t[i:i+3*nv],float).reshape(-1,3); i+=3*nv
    F=np.array(t[i:i+4*nf],int).reshape(-1,4)[:,1:]
    return V,F
def sub(V,F):
    e=np.concatenate([F[:,[0,1]],F[:,[1,2]],F[:,[2,0]]]); k=np.sort(e,1)
    u,inv=np.unique(k,axis=0,return_inverse=True)
    M=(V[u[:,0]]+V[u[:,1]])/2; n=len(V); m=inv.reshape(3,-1).T+n
    a,b,c=F[:,0],F[:,1],F[:,2]; ab,bc,ca=m[:,0],m[:,1],m[:,2]
    F2=np.concatenate([np.stack([a,ab,ca],1),np.stack([ab,b,bc],1),np.stack([ca,bc,c],1),np.stack([ab,bc,ca],1)])
    return np.vstack([V,M]),F2
V,F=read_off(sys.argv[1])
for _ in range(int(sys.argv[2])): V,F=sub(V,F)
with open(sys.argv[3],'w') as f:
    f.write(f"OFF\n{len(V)} {len(F)} 0\n"); np.savetxt(f,V,fmt='%.9g'); np.savetxt(f,np.hstack([np.full((len(F),1),3),F]),fmt='%d')
print(len(V),len(F))
