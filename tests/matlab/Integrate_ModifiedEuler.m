function [tout,yout] = Integrate_ModifiedEuler(odefun,tspan,Ts,y0,par)
%The seed's modified Euler method (TU Delft "Advanced Dynamics", homework 8),
%the oracle of dynkit.integrate('heun', ...) in tests/matlab/run_all.m.
tout=(tspan(1):Ts:tspan(end))';
numsteps=length(tout);
numstates=length(y0);
yout=zeros(numsteps,numstates);
y_n=y0;
for n=1:numsteps
  t_n=tout(n);
  t_nplus1=t_n+Ts;
  yout(n,:)=y_n;
  dy_n=feval(odefun,t_n,y_n',par)';
  ytilde_nplus1=y_n+Ts*dy_n;
  dytilde_nplus1=feval(odefun,t_nplus1,ytilde_nplus1',par)';
  y_nplus1=y_n+.5*Ts*(dytilde_nplus1+dy_n);
  y_n=y_nplus1;
end
