#!/usr/bin/python3
"""Amplitude ratio per period of a damped spring-mass oscillator (material.damping)
against each integrator's own analytic step, as tests/app/test_spring_damping.cpp
measures it, through the atssim binary (docs/accuracy.md).

  scripts/damped_oscillator.py explicit:semi_euler explicit:midpoint explicit:rk4 vbd:semi_euler xpbd:semi_euler sosd:semi_euler jpgd:semi_euler
"""
import cmath, math, os, subprocess, sys, tempfile

import h5py

B=os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'build', 'release', 'atssim')
T=tempfile.mkdtemp()
k=100.0; beta=0.002; m=0.2*0.5/3; fps=600; sub=4; frames=600
w2=k/m; g=beta*w2; h=1/(fps*sub)
def own(integ, gg):
    if integ=='semi_euler':
        tr=2-h*h*w2-h*gg; det=1-h*gg; lam=complex(0.5*tr, math.sqrt(det-0.25*tr*tr))
    else:
        z=h*complex(-0.5*gg, math.sqrt(w2-0.25*gg*gg))
        lam={'midpoint':1+z+z*z/2,'rk4':1+z+z*z/2+z**3/6+z**4/24,'implicit':1/(1-z)}[integ]
    return abs(lam)**(2*math.pi/abs(cmath.phase(lam)))
for method,integ in [(a,b) for a,b in [x.split(':') for x in sys.argv[1:]]]:
    y=f"""simulation: {{fps: {fps}, substeps: {sub}, iterations: 16, frames: {frames}, gravity: [0, 0, 9.81]}}
objects:
  - grid: {{size: [1, 1], resolution: [2, 2]}}
    transform: {{translate: [-0.5, 0, -0.5]}}
    material: {{density: 0.2, stretch_stiffness: {k}, damping: {beta}}}
    pins: {{vertices: [0, 1, 2]}}
solver: {{method: {method}, integrator: {integ}}}
"""
    open(os.path.join(T,'o.yaml'),'w').write(y)
    r=subprocess.run([B,'run',os.path.join(T,'o.yaml'),'-o',os.path.join(T,'o.h5'),'--devices','cpu','--executor','events','--quiet'],capture_output=True,text=True)
    if r.returncode: print(method, integ, 'failed', r.stderr[-300:]); continue
    z=h5py.File(os.path.join(T,'o.h5'),'r')['frames/positions'][:,3,2].astype(float)
    zeq=z[0]+m*9.81/k; p=[]
    for i in range(1,len(z)-1):
        a,b,c=z[i-1]-zeq,z[i]-zeq,z[i+1]-zeq
        if b>a and b>=c and b>0:
            den=a-2*b+c; p.append(b-0.125*(a-c)**2/den if den<0 else b)
    meas=(p[3]/p[0])**(1/3)
    ii='implicit' if method!='explicit' else integ
    print(f"{method} {integ}: measured {meas:.5f} own {own(ii,g):.5f} undamped {own(ii,0):.5f} continuous {math.exp(-0.5*g*2*math.pi/math.sqrt(w2-0.25*g*g)):.5f} rel {meas/own(ii,g)-1:+.4f}", flush=True)
